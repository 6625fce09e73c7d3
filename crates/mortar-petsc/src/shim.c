/* The C side of mortar-petsc: macros made callable, and the configuration the Rust side
   assumes checked when the crate is built (real double-precision scalars). */
#include "shim.h"

#if defined(PETSC_USE_COMPLEX)
#error "mortar-petsc needs a PETSc with real scalars (Debian: petsc-dev, not the complex build)"
#endif
#if !defined(PETSC_USE_REAL_DOUBLE)
#error "mortar-petsc needs a PETSc with double-precision scalars"
#endif

MPI_Comm mortar_petsc_comm_self(void) { return PETSC_COMM_SELF; }

int mortar_petsc_thread_serialized(void) { return MPI_THREAD_SERIALIZED; }
