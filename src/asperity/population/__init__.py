"""Stage 3-4: the asperity population and its samples.

`plan`: sample grids, keys (hashes of job specs) and derived samples;
`models`: how a sample becomes a response (representative hills of 8.2, FE
levels, the gather onto the plan's grid); `adhesive`: the same for
Lennard-Jones adhesive asperities (7.3).
"""
