"""Studies: parameter sweeps over :func:`leadscrew.simulate` that return a
pandas DataFrame and draw a diagram.

``STUDIES`` maps each study's name to its function (the command line and
notebooks look studies up there).
"""

from . import work_precision as _work_precision_module
from .work_precision import (
    ATOL_PER_RTOL,
    COLUMNS,
    CONFIGURATION_KEYS,
    REFERENCE_OPTIONS,
    default_configurations,
    exact_reference,
    plot_work_precision,
    work_precision,
)

STUDIES = {"work_precision": work_precision}

__all__ = ["STUDIES", *_work_precision_module.__all__]
