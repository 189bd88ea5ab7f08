"""The volume-of-fluid CFD step with OpenFOAM (interFoam, v1912 from Debian's ``openfoam``).

- `sloshkit.cfd.foam`: a small, tested writer of OpenFOAM dictionary syntax (pure).
- `sloshkit.cfd.spec`: what defines a case (`CaseSpec`, SI units).
- `sloshkit.cfd.excitation`: container motions and the acceleration table (pure).
- `sloshkit.cfd.mesh`, `sloshkit.cfd.fields`, `sloshkit.cfd.case`: the O-grid, the initial
  fill and fluids, and every file of the case (pure: return file texts).
- `sloshkit.cfd.state`: complete time folders, mesh checks, process limits (no processes).
- `sloshkit.cfd.run`: the only module that starts processes (blockMesh, setFields,
  decomposePar, interFoam, mpirun), with progress, interruption and resume.
- `sloshkit.cfd.results`: parsing of function-object output into signals (pure).
- `sloshkit.cfd.pipeline`: run + analyse + calibrate, used by the CLI and the report.
"""
