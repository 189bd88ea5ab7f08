"""The file and unit edge: units, CSV/JSON tables, model files, scenario files, output paths.

- `sloshkit.io.units`: ``"20.5mm"`` -> 0.0205 (a strict grammar and a fixed unit table).
- `sloshkit.io.tables`: CSV and whitespace tables, motion files.
- `sloshkit.io.models`: the model file (one serialisation of `SloshModel`).
- `sloshkit.io.scenario`: scenario TOML files.
- `sloshkit.io.schema`: typed reading of scenario and model files (one line naming the key).
- `sloshkit.io.outputs`: output paths checked before any work; staged folder outputs.
"""
