"""Finding eomc and building a spec's shared library into its cache.

The library is built by ``eomc build SPEC --shared --cache``: into the same
cache ``eomc run`` keeps its simulators in ($EOMC_CACHE_DIR, else
$XDG_CACHE_HOME/eomc or ~/.cache/eomc), keyed by the spec's text and the
options, so loading a spec a second time builds nothing.
"""

import os
import shutil
import subprocess

from ._errors import EomcError, FileNotFound, raise_for, warn_lines


def compiler():
    """The eomc to build with: $EOMC; else, for a source checkout, the
    README's build directory (build/compiler/eomc beside this package);
    else eomc on the PATH (an installed one)."""
    env = os.environ.get("EOMC")
    if env:
        return env
    here = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    local = os.path.join(here, "build", "compiler", "eomc")
    if os.access(local, os.X_OK):
        return local
    found = shutil.which("eomc")
    if found:
        return found
    raise EomcError("eomc not found: set EOMC to the compiler's path, build it "
                    "(meson compile -C build eomc eomcrt), or install it")


def build(spec, scene=None, form=None, fix=None, extended=False, jacobian=None,
          imports=(), effects=None):
    """The path of spec's shared library, built unless the cache has it;
    imports: the import's flags, for a model file (``--floating``, ...)."""
    if not os.path.exists(spec):
        raise FileNotFound("cannot read %s: no such file" % spec, spec)
    argv = [compiler(), "build", spec, "--shared", "--cache"] + list(imports)
    if scene is not None:
        argv += ["--scene", scene]
    if form is not None:
        argv += ["--form", form]
    for name, value in (fix or {}).items():
        argv += ["--fix", "%s=%r" % (name, float(value))]
    if extended:
        argv.append("--extended")
    if jacobian is not None:
        argv += ["--jacobian", jacobian]
    if effects is not None:
        argv += ["--effects", effects if isinstance(effects, str) else ",".join(effects)]
    p = subprocess.run(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    raise_for(p.returncode, p.stderr)
    warn_lines(p.stderr, stacklevel=4)
    return p.stdout.strip().splitlines()[-1]
