"""The bodies' constitutive laws: isotropic elasticity (`elastic`), J2 plasticity (`j2`),
Bodner-Partom viscoplasticity with damage (`bodner_partom`; report 3.1-3.2, 5)."""
