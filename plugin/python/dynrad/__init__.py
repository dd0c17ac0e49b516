"""dynrad: radiosity for architectural models, from Python.

    import dynrad
    result = dynrad.solve("samples/daylight_clear.json", quality="draft")
    result["radiosity"]            # (n, 3) per output vertex
    result["grids"]["room"]        # {"points": (k, 3), "illuminance": (k,)} in lx
    result["report"]["stopped_by"]

See docs/hosts.md.
"""
from ._dynrad import InputError, __version__, solve, solve_arrays

__all__ = ["InputError", "__version__", "solve", "solve_arrays"]
