"""Closed-form references: Hertz contact of one asperity (6.1) and the
Greenwood-Williamson interface (7.1)."""
