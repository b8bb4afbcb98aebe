"""The studies: what accuracy costs, `hertz` (one FE asperity at every preset and along a
refinement sequence, 6.1) and `scenes` (whole scenes at every preset); `plane_strain`
(plane-strain asperities pressed by a flat, 6.3.2, 6.3.3); `uniaxial` (Bodner-Partom
material points under the report's uniaxial histories, 5, 6.3.1, 8.2.1); `summit_scale`
(summits against the lateral scale); `adhesion` (smooth elastic aluminum asperities with
adhesion, 7.3, Fig. 7.6)."""
