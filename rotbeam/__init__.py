"""rotbeam: dynamic versus quasi-static response of a cantilevered beam rotated harmonically."""

from importlib.metadata import PackageNotFoundError, version

# the one version is pyproject.toml's, read from the installed package's metadata
try:
    __version__ = version("rotbeam")
except PackageNotFoundError:  # not installed: the source tree on PYTHONPATH only
    __version__ = "0+unknown"
