"""The version of sloshkit (base layer: any module may read it; ``sloshkit.__version__``)."""

__version__ = "0.1.0"
