"""The log of a rule's job: everything printed, every warning and the full error, in snakemake.log[0]."""

import contextlib
import logging
import sys
import traceback
import warnings


@contextlib.contextmanager
def logged(path):
    """Send stdout, stderr, warnings and the traceback of any error to ``path`` (and the error to stderr)."""
    with open(path, "w", buffering=1) as log, contextlib.redirect_stdout(log), contextlib.redirect_stderr(log):
        warnings.formatwarning = lambda message, category, *args, **kwargs: f"{category.__name__}: {message}\n"
        logging.basicConfig(stream=log, level=logging.INFO, format="%(message)s", force=True)
        try:
            yield log
        except BaseException as err:
            traceback.print_exc(file=log)
            print(f"{type(err).__name__}: {err}", file=sys.__stderr__)
            raise
