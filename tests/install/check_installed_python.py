"""Imports the installed ffdkit Python package (PYTHONPATH = its dist-packages folder) and runs
a PyGeM-style deformation: a 2x2x2 box whose far x face moves by 0.5 scales x by 1.5."""
import os
import sys

import numpy as np

import ffdkit
from ffdkit.pygem import FFD

prefix = os.path.realpath(sys.argv[1])
assert os.path.realpath(ffdkit.__file__).startswith(prefix), (ffdkit.__file__, prefix)
ffd = FFD([2, 2, 2])
ffd.array_mu_x[1, :, :] = 0.5
points = np.array([[0.5, 0.5, 0.5], [1.0, 0.2, 0.3], [2.0, 0.0, 0.0]])
out = ffd(points)
assert np.allclose(out, [[0.75, 0.5, 0.5], [1.5, 0.2, 0.3], [2.0, 0.0, 0.0]], rtol=0, atol=1e-14), out
print("installed ffdkit", ffdkit.__version__, "from", os.path.dirname(ffdkit.__file__))
