"""rotbeam: dynamic versus quasi-static response of a cantilevered beam rotated harmonically."""

__version__ = "0.1.0"
