import os
import sys

# tests/helpers is importable as `helpers` from every test module.
sys.path.insert(0, os.path.dirname(__file__))
