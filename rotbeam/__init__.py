"""rotbeam: dynamic versus quasi-static response of a cantilevered beam rotated harmonically."""

__version__ = "0.1.0"

#: Bumped whenever a change alters simulated numbers: the workflow's simulation rules carry it
#: in params:, so that Snakemake reruns them (it does not track the package's source files).
MODEL_VERSION = "3"
