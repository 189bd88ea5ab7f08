"""Before a run: the case written to disk, the host checked for OpenFOAM, the expected mesh
size (no processes started here: those are in `sloshkit.cfd.run`)."""

from __future__ import annotations

import json
import os
import shutil
import tempfile
from pathlib import Path

from sloshkit.cfd.case import CaseSpec, case_files, mesh_layout, spec_summary
from sloshkit.cfd.state import CfdError
from sloshkit.errors import InputError


def openfoam_environment() -> dict[str, str]:
    """The environment the v1912 tools need: WM_PROJECT_DIR set, MPI allowed as root, PWD
    dropped (it triggers a 'PWD is not the cwd()' warning).

    Returns
    -------
    dict of str to str

    Examples
    --------
    >>> openfoam_environment()["OMPI_ALLOW_RUN_AS_ROOT"]
    '1'
    """
    environment = {k: v for k, v in os.environ.items() if k != "PWD"}
    environment.setdefault("WM_PROJECT_DIR", "/usr/share/openfoam")
    environment["OMPI_ALLOW_RUN_AS_ROOT"] = "1"
    environment["OMPI_ALLOW_RUN_AS_ROOT_CONFIRM"] = "1"
    environment["OMPI_MCA_rmaps_base_oversubscribe"] = "1"
    return environment


def require_openfoam(processes: int = 1) -> None:
    """Raise `CfdError` unless the OpenFOAM tools are on the PATH, and `InputError` for
    ``processes`` > 1 without ``mpirun``.

    Parameters
    ----------
    processes : int
        MPI processes the run will use.

    Returns
    -------
    None

    Raises
    ------
    CfdError
        OpenFOAM missing.
    InputError
        ``processes`` > 1 without ``mpirun`` or ``decomposePar``.

    Examples
    --------
    >>> import shutil
    >>> if shutil.which("interFoam"):
    ...     require_openfoam(1)
    """
    missing = [
        tool
        for tool in ("blockMesh", "checkMesh", "setFields", "interFoam")
        if shutil.which(tool) is None
    ]
    if missing:
        raise CfdError(
            "OpenFOAM is not installed (missing " + ", ".join(missing) + "): "
            "apt-get install -y openfoam"
        )
    if processes > 1:
        for tool in ("mpirun", "decomposePar"):
            if shutil.which(tool) is None:
                raise InputError(
                    "np",
                    processes,
                    f"needs {tool}, which is not on the PATH",
                    "install Open MPI (apt-get install openmpi-bin) or use --np 1",
                )


#: Characters OpenFOAM v1912 takes in a case's absolute path: its file names refuse white
#: space and quotes, expand ``$`` and ``~``, and the case's Allrun is a shell script, so
#: only these are accepted (ASCII letters, digits and ``/ . _ - + = , @``).
CASE_PATH_CHARACTERS = frozenset(
    "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789/._-+=,@"
)


def check_case_path(case: Path | str, parameter: str = "case") -> Path:
    """Refuse a case folder whose absolute path OpenFOAM would not accept, before anything is
    written (a relative path is checked with the working folder in front of it).

    Parameters
    ----------
    case : Path or str
        The case folder (``--case``; a campaign folder for ``cfd sweep --out``).
    parameter : str
        The option that named it.

    Returns
    -------
    Path
        ``case`` as a Path.

    Raises
    ------
    InputError
        Naming the first character OpenFOAM would refuse and where it is.

    Examples
    --------
    >>> check_case_path("/tmp/vial-decay").name
    'vial-decay'
    >>> from sloshkit.errors import InputError
    >>> try:
    ...     check_case_path("/tmp/my vial")
    ... except InputError as error:
    ...     print(error.valid.split(";")[0])
    holds ' ' (a space) at character 8 of the absolute path /tmp/my vial
    """
    path = Path(case)
    absolute = os.path.abspath(path)
    for position, character in enumerate(absolute, start=1):
        if character not in CASE_PATH_CHARACTERS:
            names = {" ": "a space", "\n": "a line break", "\t": "a tab"}
            shown = names.get(character, "not ASCII" if ord(character) > 127 else "")
            visible = character.encode("utf-8", "backslashreplace").decode("ascii", "replace")
            printable = absolute.encode("utf-8", "backslashreplace").decode("ascii", "replace")
            raise InputError(
                parameter,
                str(path).encode("utf-8", "backslashreplace").decode("ascii", "replace"),
                f"holds {visible!r}{f' ({shown})' if shown else ''} at character {position} of "
                f"the absolute path {printable}; OpenFOAM v1912 takes only ASCII letters, "
                "digits and / . _ - + = , @ in a case path",
                "choose a folder whose full path has none of the others",
            )
    return path


def write_case(spec: CaseSpec, case: Path, overwrite: bool = False) -> Path:
    """Write the case files into ``case`` (sloshkit-case.json last: it marks a whole case).

    An existing non-empty folder is refused unless ``overwrite`` is given and it holds a
    sloshkit case, whose contents are then replaced; other folders are never emptied.

    Parameters
    ----------
    spec : CaseSpec
        The case.
    case : Path
        The case folder.
    overwrite : bool
        Replace an existing sloshkit case.

    Returns
    -------
    Path
        ``case``.

    Raises
    ------
    InputError
        The folder exists and is not empty (and not a sloshkit case, with ``overwrite``).

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> from sloshkit.cfd.spec import CaseSpec
    >>> from sloshkit.model.liquids import get_liquid
    >>> spec = CaseSpec(0.0205, 0.039, get_liquid("water-25C"), cells_per_radius=8)
    >>> case = write_case(spec, Path(tempfile.mkdtemp()) / "vial")
    >>> (case / "Allrun").is_file(), (case / "sloshkit-case.json").is_file()
    (True, True)
    """
    check_case_path(case)
    if case.exists() and not case.is_dir():
        raise InputError("case", str(case), "is a file, not a folder")
    if case.exists() and any(case.iterdir()):
        if not overwrite:
            raise InputError(
                "case", str(case), "exists and is not empty (use --overwrite or --resume)"
            )
        if not (case / "sloshkit-case.json").is_file():
            raise InputError(
                "case",
                str(case),
                "is not empty and not a sloshkit case: --overwrite only replaces sloshkit cases",
            )
        for entry in case.iterdir():
            if entry.is_dir() and not entry.is_symlink():
                shutil.rmtree(entry)
            else:
                entry.unlink()
    # Written into a staging folder beside the case and moved into place: an interruption
    # leaves either no case or a whole one (the staging folder is removed on any exception).
    case.parent.mkdir(parents=True, exist_ok=True)
    staging = Path(tempfile.mkdtemp(prefix=f".{case.name}.staging-", dir=case.parent))
    try:
        for relative, text in case_files(spec).items():
            path = staging / relative
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(text, encoding="utf-8")
        (staging / "Allrun").chmod(0o755)
        (staging / "sloshkit-case.json").write_text(
            json.dumps(spec_summary(spec), indent=2), encoding="utf-8"
        )
        staging.chmod(0o755)
        if case.exists():
            case.rmdir()
        staging.rename(case)
    except BaseException:
        shutil.rmtree(staging, ignore_errors=True)
        raise
    return case


def expected_cells(spec: CaseSpec) -> int:
    """Cells blockMesh will make for ``spec``.

    Parameters
    ----------
    spec : CaseSpec
        The case.

    Returns
    -------
    int

    Examples
    --------
    >>> from sloshkit.cfd.spec import CaseSpec
    >>> from sloshkit.model.liquids import get_liquid
    >>> spec = CaseSpec(0.0205, 0.039, get_liquid("water-25C"), cells_per_radius=8)
    >>> expected_cells(spec)
    6336
    """
    return mesh_layout(spec).cells
