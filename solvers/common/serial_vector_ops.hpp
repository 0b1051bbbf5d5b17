#pragma once
// The vector operations of rodlab's serial N_Vectors, compiled with the project's optimisation.
//
// Debian 12's SUNDIALS 6.4.1 is built without optimisation (its objects keep every loop
// variable on the stack: `objdump -d libsundials_nvecserial.so.6`), and IDA and KINSOL do all
// their O(n) work through the N_Vector operations: in `ida` (N = 50, rtol = atol = 1e-10) the
// weighted RMS norm alone was 28 % of the run (perf). SUNDIALS lets a vector carry its own
// operations (the N_Vector ops table, copied into every clone the integrators make), so the
// library stays Debian's and only these kernels are replaced.
//
// Every operation computes what SUNDIALS' serial vector defines, element by element in the same
// order and with the same special cases (N_VLinearSum's a == b and a == -b forms, N_VScale's
// c = +-1): results are bit for bit those of the library's own (tests/common/
// test_serial_vector_ops.cpp compares every operation on the same inputs). Fused and vector-array
// operations stay off, as in a plain N_VNew_Serial.
#include <nvector/nvector_serial.h>

namespace rodlab::solvers::sundials {

/// Replaces the element-wise and reduction operations of the serial vector v (and so of every
/// clone of it) with the compiled ones above. v must be a serial vector.
void use_compiled_serial_ops(N_Vector v);

}  // namespace rodlab::solvers::sundials
