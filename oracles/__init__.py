"""Adapters that put libraries (and the exact reference) on the reference's conventions,
and the ``ddg-oracle`` command line."""
