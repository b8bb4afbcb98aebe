"""The laws of the surface against the rigid flat: penalty contact (`penalty`, report
3.3), Lennard-Jones adhesion (`adhesion`, 3.4), sliding resistance (`sliding`, 3.3.4)."""
