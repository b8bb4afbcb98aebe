"""What a job runs: one asperity pressed by the flat, elastic (`elastic`), along an
inelastic history (`inelastic`: the step's equilibrium `inelastic_model`, its steps
`history_march`, on meshes that follow the contact: `remesh`), with adhesion
(`adhesive`: the model `adhesive_model`, the path `adhesive_trace`), and the
three-dimensional asperity pressed and slid (`solid3d`: `flat_motion`,
`sliding_model`, its steps `sliding_march`).  The drivers that march in time run one
loop, `march`; the elastic and adhesive paths under a prescribed flat position are
followed by one driver, `path`."""
