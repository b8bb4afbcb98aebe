"""What accuracy costs: `hertz` (one FE asperity at every preset and along a
refinement sequence, 6.1) and `scenes` (whole scenes at every preset)."""
