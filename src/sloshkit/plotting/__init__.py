"""Figures of result objects (matplotlib, imported only when a figure is drawn)."""
