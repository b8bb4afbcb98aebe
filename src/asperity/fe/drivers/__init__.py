"""What a job runs: one asperity pressed by the flat, elastic (`elastic`), along an
inelastic history (`inelastic`, on meshes that follow the contact: `remesh`), with
adhesion (`adhesive`), and the three-dimensional asperity pressed and slid (`solid3d`)."""
