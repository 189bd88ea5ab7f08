"""The volume-of-fluid CFD step with OpenFOAM (interFoam, v1912 from Debian's ``openfoam``).

- `sloshkit.cfd.foam`: a small, tested writer of OpenFOAM dictionary syntax (pure).
- `sloshkit.cfd.case`: case generation from a container, a liquid and an excitation (pure:
  returns file texts).
- `sloshkit.cfd.run`: the only module that starts processes (blockMesh, setFields,
  decomposePar, interFoam, mpirun), with progress from the solver log.
- `sloshkit.cfd.results`: parsing of function-object output into signals (pure).
- `sloshkit.cfd.pipeline`: run + analyse + calibrate, used by the CLI and the report.
"""
