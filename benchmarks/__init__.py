"""Speed and wall-time measurements (not collected by pytest)."""
