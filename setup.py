"""ament_python package allocator_pkg (the repository root)."""

from glob import glob

from setuptools import find_packages, setup

PACKAGE = "allocator_pkg"

setup(
    name=PACKAGE,
    version="0.1.0",
    packages=find_packages(include=[PACKAGE, f"{PACKAGE}.*"]),
    data_files=[
        ("share/ament_index/resource_index/packages", [f"resource/{PACKAGE}"]),
        (f"share/{PACKAGE}", ["package.xml"]),
        (f"share/{PACKAGE}/config", sorted(glob("config/*.yaml"))),
        (f"share/{PACKAGE}/launch", sorted(glob("launch/*.py"))),
    ],
    install_requires=["setuptools", "numpy", "osqp", "daqp", "highspy", "pyyaml"],
    extras_require={"tools": ["scipy", "matplotlib", "tqdm"],      # allocator-capability and the demo
                    "cluster": ["dask[distributed]"]},  # allocator-capability --dnv-level3 --scheduler
    zip_safe=True,
    maintainer="allocator_pkg maintainers",
    maintainer_email="allocator@example.com",
    description="Thrust allocation node for marine and underwater vehicles (ROS 2 Jazzy).",
    license="Apache-2.0",
    python_requires=">=3.10",
    entry_points={
        "console_scripts": [
            "allocator_node = allocator_pkg.ros.node:main",
            "allocator_lifecycle_node = allocator_pkg.ros.lifecycle_node:main",
            "allocator-ctl = allocator_pkg.cli.allocator_ctl:main",
            "allocator-capability = allocator_pkg.cli.allocator_capability:main",
            "allocator-explicit = allocator_pkg.cli.allocator_explicit:main",
            "allocator-sim = allocator_pkg.cli.allocator_sim:main",
        ],
        "pytest11": ["allocator_pkg = allocator_pkg.testing.plugin"],     # the allocator_harness fixture
    },
)
