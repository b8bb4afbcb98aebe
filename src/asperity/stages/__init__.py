"""The stages of the pipeline as functions of data (DESIGN.md, task graph)."""

from asperity.stages.common import *  # noqa: F401,F403
