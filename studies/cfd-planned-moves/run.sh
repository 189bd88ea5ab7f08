#!/usr/bin/env bash
# The CFD runs of this study (README.md), in a scratch folder given as $1 (default ./runs).
# Each case: the plan (sloshkit plan --path-from-poses ...), then `sloshkit cfd run
# --excitation poses` on its export and `sloshkit cfd validate`. About 2 min per case at
# 12 cells per radius, 9 min at 16 and 30 min at 20 (one process, 2-core machine).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
out=${1:-runs}
mkdir -p "$out" && cd "$out"
measured="$root/tests/data/measured-3d/poses/TRD_2D_0.3m_2.4s_270deg.csv"
container=(--radius 49mm --fill-height 80mm --liquid water-20C --damping-ratio 0.0066)
limits=(--max-residual-height 2mm --vmax 2m/s --amax 10m/s^2 --jmax 100m/s^3)
lifted=(--max-angular-velocity none --max-angular-acceleration none)

plan() {  # plan NAME [options...]: the export NAME.csv and its JSON
  local name=$1
  shift
  sloshkit plan --path-from-poses "$measured" "${container[@]}" "${limits[@]}" "$@" \
    --out "$name.csv" --json > "$name.json"
}
cfd() {  # cfd CASE POSES CELLS_PER_RADIUS END_TIME
  sloshkit cfd run --case "$1" --excitation poses --pose-file "$2" --cells-per-radius "$3" \
    --end-time "$4" --np 1 "${container[@]}" --wall-height 140mm --json > "$1.json"
  sloshkit cfd validate --case "$1" --reuse "${container[@]}" --wall-height 140mm \
    --plot "$1.png" --json > "$1-validate.json"
}

plan tilt --max-slosh-height 15mm "${lifted[@]}" --tilt-compensation --max-tilt 30deg
plan retime --max-slosh-height 15mm "${lifted[@]}" --method retime
plan tilt10 --max-slosh-height 10mm "${lifted[@]}" --tilt-compensation --max-tilt 30deg
plan angular --max-slosh-height 15mm --tilt-compensation --max-tilt 30deg
plan angle15 --max-slosh-height 15mm "${lifted[@]}" --tilt-compensation --max-tilt 30deg \
  --max-surface-angle 15deg
plan rtangle --max-slosh-height 15mm "${lifted[@]}" --method retime --max-surface-angle 15deg
# pick-and-place: 0.3 m with a 0.1 m lift, 90 degrees about the vertical
printf 'x [mm],y [mm],z [mm],yaw [deg]\n0,0,0,0\n300,0,100,90\n' > pick.csv
for method in retime tilt; do
  sloshkit plan --path pick.csv "${container[@]}" "${limits[@]}" --max-slosh-height 15mm \
    "${lifted[@]}" --tilt-compensation --max-tilt 30deg --method "$method" \
    --out "pnp_$method.csv" --json > "pnp_$method.json"
done
# the tilt plan without its turn about the container's axis (the axis direction unchanged)
python - <<'PY'
import numpy as np
from scipy.spatial.transform import Rotation
from sloshkit.io.poses import read_pose_file

poses = read_pose_file("tilt.csv")
axis = Rotation.from_quat(poses.quaternion_xyzw).apply([0.0, 0.0, 1.0])
normal = np.cross([0.0, 0.0, 1.0], axis)
sine = np.linalg.norm(normal, axis=1)
rotvec = np.zeros_like(axis)
turned = sine > 1e-12
angle = np.arctan2(sine[turned], axis[turned, 2])
rotvec[turned] = normal[turned] / sine[turned, None] * angle[:, None]
quaternion = Rotation.from_rotvec(rotvec).as_quat()
rows = ["t,x,y,z,qx,qy,qz,qw"] + [
    ",".join(f"{v:.12g}" for v in (t, *p, *q))
    for t, p, q in zip(poses.time_s, poses.position_m, quaternion)
]
open("noyaw.csv", "w").write(
    "# units: t [s]; x, y, z [m]; qx, qy, qz, qw [-] (container to world, scalar last); z up\n"
    + "\n".join(rows) + "\n")
PY
# pure tilts about the bottom centre: 5 and 30 degrees, septic ramps of 0.5 s, held 0.3 s
python - <<'PY'
import numpy as np
from scipy.spatial.transform import Rotation

step = 0.002
t = np.arange(0.0, 1.3 + step / 2, step)


def septic(u):
    u = np.clip(u, 0.0, 1.0)
    return u**4 * (35 - 84 * u + 70 * u**2 - 20 * u**3)


for name, degrees in (("pitch5", 5.0), ("pitch", 30.0)):
    angle = np.radians(degrees) * (septic(t / 0.5) - septic((t - 0.8) / 0.5))
    rotvec = np.column_stack([angle, 0.0 * angle, 0.0 * angle])
    quaternion = Rotation.from_rotvec(rotvec).as_quat()
    rows = ["t,x,y,z,qx,qy,qz,qw"] + [
        ",".join(f"{v:.12g}" for v in (ti, 0.0, 0.0, 0.0, *qi)) for ti, qi in zip(t, quaternion)
    ]
    open(f"{name}.csv", "w").write(
        "# units: t [s]; x, y, z [m]; qx, qy, qz, qw [-] (container to world, scalar last); z up\n"
        + "\n".join(rows) + "\n")
PY

cfd meas12 "$measured" 12 6s
cfd meas16 "$measured" 16 6s
cfd rt12 retime.csv 12 4s
cfd trd12 tilt.csv 12 3.5s
cfd trd16 tilt.csv 16 3.5s
cfd trd20 tilt.csv 20 3.5s
cfd noyaw12 noyaw.csv 12 3.5s
cfd angular12 angular.csv 12 4s
cfd tilt10_12 tilt10.csv 12 3.5s
cfd tilt10_16 tilt10.csv 16 3.5s
cfd rtangle12 rtangle.csv 12 4.3s
cfd angle15_12 angle15.csv 12 3.5s
cfd angle15_16 angle15.csv 16 3.5s
cfd pnp_retime12 pnp_retime.csv 12 2.8s
cfd pnp_tilt12 pnp_tilt.csv 12 2.8s
cfd pitch5_12 pitch5.csv 12 3.3s
cfd pitch12 pitch.csv 12 3.3s
python "$here/azimuthal.py" . meas12 meas16 rt12 rtangle12 trd12 trd16 trd20 noyaw12 \
  angular12 tilt10_12 tilt10_16 angle15_12 angle15_16 pnp_retime12 pnp_tilt12 pitch5_12 \
  pitch12
