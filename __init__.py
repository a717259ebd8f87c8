"""Not the package: the root of eomc's repository, imported as one.

A clone of the repository is a folder named eomc whose package is its
subfolder eomc/.  A script run from the folder above the clone has that
folder on sys.path, so ``import eomc`` finds the clone first; without this
file Python took it for an empty namespace package, and the script failed
later with ``module 'eomc' has no attribute 'load'``.  This file makes the
import say so.  When the package is on the path too (``PYTHONPATH=eomc``,
or an installed one), it is the one meant, and it is imported instead, as
Python would have done without this file.
"""

import importlib.machinery
import importlib.util
import os
import sys


def _package():
    here = os.path.dirname(os.path.realpath(__file__))
    shown = os.path.dirname(os.path.abspath(__file__))  # as the path has it (a link)
    # the path without the folders that hold this repository as eomc/
    rest = [p for p in sys.path
            if os.path.realpath(os.path.join(p or os.curdir, __name__)) != here]
    spec = importlib.machinery.PathFinder.find_spec(__name__, rest)
    if spec is None or spec.origin is None or spec.submodule_search_locations is None:
        raise ImportError(
            "%s is eomc's repository, not its package: it was imported as one because %s, "
            "the folder above it, is on sys.path (a script's own folder is). The package "
            "is its subfolder eomc/: put the repository on the path (PYTHONPATH=%s python3 "
            "SCRIPT), or run from inside it (docs/python.md, \"Where the package comes "
            "from\")" % (shown, os.path.dirname(shown), shown), name=__name__)
    module = importlib.util.module_from_spec(spec)
    sys.modules[__name__] = module  # the import returns what sys.modules holds
    spec.loader.exec_module(module)


_package()
