"""The references the pipeline is checked against.

`hertz`: the closed-form Hertz contact of one asperity (6.1); `kogut_etsion`: the
elastic-plastic sphere of Kogut and Etsion's finite element fits; `adhesion`: the JKR and
Maugis-Dugdale adhesive sphere (3.4.1); `greenwood_williamson`: the Greenwood-Williamson
interface (7.1); `boundary_element`: the deterministic contact of a whole height map against a rigid flat (ContactMechanics), the reference of the
`deterministic_reference` scene."""
