"""The file and unit edge: units (pint), CSV/JSON tables, model files, scenario files.

- `sloshkit.io.units`: ``"20.5mm"`` -> 0.0205 (the only module that imports pint).
- `sloshkit.io.tables`: atomic writes, CSV and JSON tables, motion files.
- `sloshkit.io.models`: the model file (one serialisation of `SloshModel`).
- `sloshkit.io.scenario`: scenario TOML files.
"""
