"""A scene's sections as objects in SI. `materials`: the scene's material in
SI and the constitutive body it names (report 3.2.2)."""
