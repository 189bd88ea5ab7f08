"""The volume-of-fluid CFD step with OpenFOAM (interFoam, v1912 from Debian's ``openfoam``).

- `sloshkit.cfd.foam`: a small, tested writer of OpenFOAM dictionary syntax (pure).
- `sloshkit.cfd.spec`: what defines a case (`CaseSpec`, SI units).
- `sloshkit.cfd.requests`: the case options of a command in SI (`CaseRequest`), checked and made
  a `CaseSpec`.
- `sloshkit.cfd.excitation`: container motions and the acceleration table (pure).
- `sloshkit.cfd.mesh`, `sloshkit.cfd.fields`, `sloshkit.cfd.system`, `sloshkit.cfd.case`: the
  O-grid (uniform, or with a graded wall annulus), the initial fill and fluids, the system
  dictionaries, and every file of the case (pure: return file texts).
- `sloshkit.cfd.state`: complete time folders, mesh checks (the measured stability limit of
  wall-graded O-grids), process limits, run outcomes (no processes).
- `sloshkit.cfd.prepare`: writing a case, checking the host for OpenFOAM (no processes).
- `sloshkit.cfd.run`: runs the tools (blockMesh, setFields, decomposePar, interFoam, mpirun),
  with progress, interruption and resume; `sloshkit.cfd.processes` starts and stops them (no
  process outlives an interruption). The only modules that start processes.
- `sloshkit.cfd.results`: parsing of function-object output into signals (pure).
- `sloshkit.cfd.force_signal`: the wall force as the decay signal (noise ratio, step alternation).
- `sloshkit.cfd.analysis`: frequency and damping of a finished case.
- `sloshkit.cfd.pipeline`: case from a model, run, and `validate` (CFD against the pendulum
  model), used by the CLI and the report; `sloshkit.cfd.validation` holds its result object.
- `sloshkit.cfd.pose_validation`: pose-driven cases against the 3-D model.
- `sloshkit.cfd.campaign`: campaigns of cases on Dask.
"""
