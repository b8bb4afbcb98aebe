"""The bodies' constitutive laws: isotropic elasticity (`elastic`), J2 plasticity (`j2`),
Bodner-Partom viscoplasticity with damage (`bodner_partom`: its state
`bodner_partom_state`, its implicit and explicit updates `bodner_partom_implicit`,
`bodner_partom_explicit`; report 3.1-3.2, 5), and the Mandel-vector algebra they
share (`tensors`)."""
