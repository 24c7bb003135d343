"""gearcli: design check and torsional dynamics of multi-stage helical gear reducers."""

__version__ = "0.1.0"
