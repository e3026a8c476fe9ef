from setuptools import setup

package_name = "teleop_keys"

setup(
    name=package_name,
    version="0.0.1",
    packages=[package_name],
    data_files=[
        ("share/ament_index/resource_index/packages", ["resource/" + package_name]),
        ("share/" + package_name, ["package.xml"]),
    ],
    install_requires=["setuptools"],
    entry_points={"console_scripts": ["teleop_keyboard = teleop_keys.keyboard:main"]},
)
