"""Bodner-Partom material points under uniaxial histories (report 5, 6.3.1, 8.2.1).

`point`: the material-point driver.  The tests of a scene, the ODE reference and the
implicit-against-explicit integrator study are a study (`asperity.studies.uniaxial`).
"""
