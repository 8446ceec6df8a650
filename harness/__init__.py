"""rbfib harness: runs study drivers, compares their results with reference/, renders reports/.

Formats (results.json, reference/<study>.yaml, studies/<name>/study.yaml): harness/FORMAT.md.
"""


class HarnessError(Exception):
    """Bad input to the harness: printed as one line, exit status 2."""
