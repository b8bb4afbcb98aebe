"""Bodner-Partom material points under uniaxial histories (report 5, 6.3.1, 8.2.1).

`point`: the material-point driver; `scene`: a scene's tests and the
implicit-against-explicit integrator study.
"""
