"""Nonlinear solution: the one Newton iteration with its line searches and step
control (`nonlinear`), Newton on the condensed contact problem of an elastic body
(`newton`; report 3.5), the adhesive problem's Newton and its tangent (`adhesive`),
arc-length continuation through folds (`arclength`), a material point under mixed
control (`mixed`), the time integration of an inelastic material and its error
(`time_error`; report 3.4, 3.6), and the reused LU of the 3-D model (`linear`)."""
