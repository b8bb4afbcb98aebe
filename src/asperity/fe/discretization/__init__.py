"""From a profile to equations: the asperity's shape (`geometry`), its meshes (`mesh`,
`adapt`), the P2 fields, strains and condensed stiffness (`assembly`, `kinematics`)."""
