"""Stages 3-4: the asperity population and the response of its samples (report 2.4,
2.5.1, 8.2, 8.3).

- `density`: the peak density of a scene (Nayak/Francis, fixed curvature, sampled)
  and the rectangle of its effective support;
- `plan`: sample grids, keys (hashes of job specs) and derived samples;
- `samples`: the plan of a scene, the response of one sample, the gather;
- `kinds`: one protocol (spec, solve, gather, ...) per asperity kind, in a registry:
  ``hertz``, ``elastic``, ``inelastic``, ``adhesive``;
- `geometry`: how a sample becomes the body of an FE job (representative and coupled
  cosine hills, spheres; job ranges; self-similar families; unloading levels);
- `gather`: FE samples interpolated onto the plan's grid, with their unloading paths.
"""
