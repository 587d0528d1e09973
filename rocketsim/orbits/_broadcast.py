"""Broadcast scalar and 3-vector arguments to flat rows for a compiled loop."""

from __future__ import annotations

import numpy as np

from rocketsim.errors import InputError


def flat_rows(scalars, vectors, names):
    """Broadcast over leading dimensions; return ``(shape, scalars, vectors)``.

    ``scalars``: arrays broadcast to ``shape`` and flattened to ``(n,)``;
    ``vectors``: arrays whose last axis has length 3, broadcast to
    ``shape + (3,)`` and flattened to contiguous ``(n, 3)``. ``names`` label
    the vectors in the error for a wrong last axis.
    """
    scalars = [np.asarray(a, dtype=float) for a in scalars]
    vectors = [np.asarray(a, dtype=float) for a in vectors]
    for vector in vectors:
        if vector.shape[-1:] != (3,):
            raise InputError(f"{'/'.join(names)} must have 3 components in their last axis",
                             field="/".join(names))
    shape = np.broadcast_shapes(*(a.shape for a in scalars), *(v.shape[:-1] for v in vectors))
    flat_scalars = [np.ascontiguousarray(np.broadcast_to(a, shape)).reshape(-1) for a in scalars]
    flat_vectors = [np.ascontiguousarray(np.broadcast_to(v, shape + (3,))).reshape(-1, 3)
                    for v in vectors]
    return shape, flat_scalars, flat_vectors
