"""The only package that touches the disk (DESIGN.md, the netCDF contract).

`netcdf`: writing a dataset atomically under the contract (units and long_name on
every variable, scene, title, history, source, config, code_version) and reading it
back; `inputs`: readers of measured profiles and height maps (text, CSV, .npy,
netCDF); `writers`: the synthetic inputs in the formats `inputs` reads; `figures`:
saving a figure atomically with the code version of its stage; `joblog`: the log of
one workflow job.
"""
