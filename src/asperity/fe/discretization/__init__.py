"""From a profile to equations: the asperity's shape (`geometry`), its meshes (`mesh`,
`adapt`), the P2 fields, strains and condensed stiffness (`assembly`, `kinematics`),
and the 3-D half model of the sliding asperity (`half_model_mesh`, `half_model`)."""
