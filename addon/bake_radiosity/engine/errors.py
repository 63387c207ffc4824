"""The bake's own error, in a module of its own so that every step (export, lamps, solve) can
raise it without importing the pipeline."""


class BakeError(RuntimeError):
    """A bake that cannot run; the message says why in words an artist can act on. Every failure
    of a bake reaches the operators and the batch command as this one type."""
