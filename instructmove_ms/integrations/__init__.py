"""Bridges to the field's training and evaluation tools, each behind an optional import; the
core and ``tasks/`` never import them."""
