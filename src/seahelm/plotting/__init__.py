"""Plotting: the only subpackage that imports matplotlib (lazily, inside functions).

Every function takes an optional ``ax=`` (or ``fig=``) and returns what it drew on.
"""
