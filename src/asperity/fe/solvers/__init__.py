"""Nonlinear solution: the one Newton iteration with its line searches (`nonlinear`)
and Newton on the condensed contact problem with continuation (`newton`; report 3.5)."""
