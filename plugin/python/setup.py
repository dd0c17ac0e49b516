"""pip install plugin/python: builds `import dynrad` with CMake and installs it.

The extension is built in DYNRAD_BUILD_DIR (default: build-python beside this
checkout's top), so a build directory that has it already (build/, after
scripts/test.sh) makes the install a copy. Needs what scripts/install-deps.sh all
installs (the compiler, CMake, the libraries, pybind11-dev, python3-dev).
"""
import os
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.dirname(os.path.dirname(HERE))


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build = os.environ.get("DYNRAD_BUILD_DIR", os.path.join(TOP, "build-python"))
        if not os.path.exists(os.path.join(build, "CMakeCache.txt")):
            subprocess.check_call(["cmake", "-S", TOP, "-B", build, "-G", "Ninja",
                                   "-DCMAKE_BUILD_TYPE=Release", "-DDYNRAD_BUILD_TESTS=OFF",
                                   "-DDYNRAD_BUILD_BENCH=OFF", "-DPython3_EXECUTABLE=" + sys.executable])
        subprocess.check_call(["cmake", "--build", build, "--target", "dynrad_python_module"])
        built = os.path.join(build, "python", "dynrad")
        module = next(f for f in os.listdir(built) if f.startswith("_dynrad") and f.endswith(".so"))
        target = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copyfile(os.path.join(built, module), target)


setup(
    name="dynrad",
    version="0.1.0",
    description="Radiosity for architectural models: lit meshes, lux on work planes, daylight",
    packages=["dynrad"],
    package_dir={"dynrad": os.path.join(HERE, "dynrad")},
    ext_modules=[Extension("dynrad._dynrad", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    python_requires=">=3.9",
    install_requires=["numpy"],
)
