"""examples/numpy_cotan.py's cotan Laplacians served over the executable protocol.

    ddg-oracle check --impl 'exec:python3 examples/exec_numpy_cotan.py'
    ddg-oracle check --impl 'exec:python3 examples/exec_numpy_cotan.py WrongCorner'

The argument names one of the classes of examples/numpy_cotan.py (default NumpyCotan).
A program in any language does the same: read a JSON request per line, write a JSON
answer per line (docs/protocol.md; examples/cpp/cotan_driver.cpp is the C++ one).
"""

import sys

import numpy_cotan          # beside this script (python puts the script's folder first)

from ddg_oracle.oracles.executable import serve

serve(getattr(numpy_cotan, sys.argv[1] if len(sys.argv) > 1 else "NumpyCotan")())
