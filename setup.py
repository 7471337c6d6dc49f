"""pip install of the tortuosity module: 'make pip-package' builds the module and the shared
library into build/pip/tortuosity, and setuptools packages that folder. Tangled from paper.nw."""
import os
import re
import subprocess

from setuptools import setup
from setuptools.dist import Distribution

ROOT = os.path.dirname(os.path.abspath(__file__))


def version():
    with open(os.path.join(ROOT, "Makefile")) as makefile:
        return re.search(r"^VERSION := (\S+)$", makefile.read(), re.M).group(1)


class WithLibrary(Distribution):
    def has_ext_modules(self):       # it holds a shared library: a wheel for this platform only
        return True


subprocess.run(["make", "-s", "-C", ROOT, "pip-package"], check=True)
setup(name="tortuosity", version=version(),
      description="Vessel tortuosity from P-spline curvature and torsion (Brummer, Hunt and Savage)",
      python_requires=">=3.9", install_requires=["numpy"],
      packages=["tortuosity"], package_dir={"tortuosity": "build/pip/tortuosity"},
      package_data={"tortuosity": ["libtortuosity.so.1"]}, distclass=WithLibrary, zip_safe=False,
      options={"build": {"build_base": "build/pip/setuptools"}, "egg_info": {"egg_base": "build/pip"}})
