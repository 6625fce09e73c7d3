/* What the Rust side of mortar-petsc sees of PETSc: its KSP interface, and the two values
   that are macros in C (the self communicator, MPI's thread level) as functions. */
#ifndef MORTAR_PETSC_SHIM_H
#define MORTAR_PETSC_SHIM_H
#include <petscksp.h>

/* PETSC_COMM_SELF: a macro over MPI_COMM_SELF, whose value depends on the MPI library. */
MPI_Comm mortar_petsc_comm_self(void);

/* MPI_THREAD_SERIALIZED: any thread may call MPI, one at a time. */
int mortar_petsc_thread_serialized(void);

#endif
