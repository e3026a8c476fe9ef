from setuptools import find_packages, setup

package_name = "py_nodes"

setup(
    name=package_name,
    version="0.0.1",
    packages=find_packages(exclude=["test"]),
    data_files=[
        ("share/ament_index/resource_index/packages", ["resource/" + package_name]),
        ("share/" + package_name, ["package.xml"]),
    ],
    install_requires=["setuptools"],
    zip_safe=True,
    entry_points={
        "console_scripts": [
            "echo_args = py_nodes.echo_args:main",
            f"crasher = {package_name}.crasher:main",
        ],
    },
)
