"""Maps the `pygem` package PyGeM's own tests import onto ffdkit.pygem, for this test run only.

The shim lives in sys.modules of the pytest process: `from pygem import CFFD` gets
ffdkit.pygem.CFFD, `from pygem.vffd import _volume` gets ffdkit's copy of PyGeM's volume function.
An installed PyGeM, if any, is not used.
"""

import sys
import types

from ffdkit import pygem as _ffdkit_pygem
from ffdkit import pygem_cffd as _ffdkit_cffd

_package = types.ModuleType("pygem")
_package.__path__ = []  # a package, so that `pygem.vffd` resolves through sys.modules
_package.__doc__ = "ffdkit.pygem, seen as pygem by PyGeM's tests"
for _name in ("FFD", "CFFD", "BFFD", "VFFD"):
    setattr(_package, _name, getattr(_ffdkit_pygem, _name))
sys.modules["pygem"] = _package
sys.modules["pygem.ffd"] = _ffdkit_pygem
for _sub in ("cffd", "bffd", "vffd"):
    sys.modules["pygem." + _sub] = _ffdkit_cffd
    setattr(_package, _sub, _ffdkit_cffd)
