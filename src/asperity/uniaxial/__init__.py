"""Bodner-Partom material points under uniaxial histories (report 5, 6.3.1, 8.2.1).

`point`: the material-point driver; `scene`: the tests of a scene (each an
`asperity.scene.UniaxialTest`), the ODE reference, and the implicit-against-explicit
integrator study.
"""
