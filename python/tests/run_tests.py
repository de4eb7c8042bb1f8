"""Runs the quadrix module's pytest suite (ctest's python_module test).

Exit 77 (ctest: skipped) with the reason when NumPy or pytest is not installed; otherwise pytest's
exit status. The module is found through PYTHONPATH (ctest sets it to the build's python/ folder).
"""
import os
import sys

try:
    import numpy  # noqa: F401
    import pytest
except ImportError as e:
    print(f"skipped: {e} (install python3-numpy and python3-pytest)")
    sys.exit(77)

here = os.path.dirname(os.path.abspath(__file__))
sys.exit(pytest.main(["-q", "-p", "no:cacheprovider", here]))
