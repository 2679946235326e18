"""The one numba decorator of the kernel.

cache=True: compiled code is stored next to the sources, so only the first process pays
the compile time. nogil=True: runs release the GIL, so threads run them in parallel.
error_model="numpy": a division by zero yields inf/nan (caught by the
driver's finiteness checks and reported as a status) instead of raising inside a kernel.
Set NUMBA_DISABLE_JIT=1 to run the kernel as plain Python for debugging.
"""

import numba as nb

kernel_jit = nb.njit(cache=True, nogil=True, error_model="numpy")
