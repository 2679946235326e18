"""The kernel runs without numba's reference counting (kernel/jit.py): a `kernel_jit`
function may not allocate an array nor hand one back, and the compiler says so."""

from __future__ import annotations

import numba
import numpy as np
import pytest

from frictiondisk.kernel.jit import kernel_jit, kernel_jit_allocating


@kernel_jit
def _first_row(a):
    return a[0]  # a view of the caller's array, returned without counting


@kernel_jit
def _sum_first_row(a):
    return _first_row(a).sum()


@kernel_jit
def _same(a):
    return a  # the caller's own array: numba allows it, the kernel's rule does not


@kernel_jit_allocating
def _sum_same(a):
    return _same(a).sum()


@kernel_jit
def _allocates(n):
    return np.empty(n).shape[0]


@kernel_jit_allocating
def _new_vector(n):
    return np.zeros(n)


@kernel_jit
def _uncounted_caller(n):
    return _new_vector(n)[0]


@kernel_jit_allocating
def _counted_caller(n):
    return _new_vector(n).shape[0]


def test_an_uncounted_function_returning_an_array_is_refused():
    with pytest.raises(numba.core.errors.TypingError, match="returning of array"):  # numba's
        _sum_first_row(np.ones((2, 3)))
    with pytest.raises(TypeError, match="_same returns an array"):  # kernel/jit.py's
        _sum_same(np.ones(3))


def test_an_uncounted_caller_of_a_function_returning_an_array_is_refused():
    with pytest.raises(TypeError, match="_new_vector returns an array"):
        _uncounted_caller(3)


def test_an_uncounted_function_cannot_allocate():
    with pytest.raises(numba.core.errors.TypingError, match="empty"):
        _allocates(3)


def test_counted_functions_pass_arrays_between_them():
    assert _counted_caller(4) == 4
