//! Finds the system's PETSc and its MPI (pkg-config), generates the bindings of the few
//! functions `src/petsc.rs` calls (bindgen over `petscksp.h`), and compiles the C shim that
//! turns PETSc's macros (the communicator, the configuration checks) into something Rust can
//! call. Without the `petsc` feature it does nothing.

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    #[cfg(feature = "petsc")]
    petsc::build();
}

#[cfg(feature = "petsc")]
mod petsc {
    use std::path::PathBuf;

    /// PETSc's functions that `src/petsc.rs` calls; bindgen brings in the types they name.
    const FUNCTIONS: &[&str] = &[
        "PetscInitialize",
        "PetscInitialized",
        "PetscFinalize",
        "PetscGetVersion",
        "PetscPushErrorHandler",
        "PetscErrorMessage",
        "PetscOptionsCreate",
        "PetscOptionsDestroy",
        "PetscOptionsInsertString",
        "PetscOptionsPush",
        "PetscOptionsPop",
        "MPI_Initialized",
        "MPI_Finalized",
        "MPI_Init_thread",
        "MPI_Finalize",
        "MatCreate",
        "MatSetSizes",
        "MatSetType",
        "MatSetBlockSize",
        "MatSeqAIJSetPreallocationCSR",
        "MatSetNearNullSpace",
        "MatNullSpaceCreateRigidBody",
        "MatNullSpaceCreate",
        "MatNullSpaceDestroy",
        "MatDestroy",
        "VecCreateSeq",
        "VecSetBlockSize",
        "VecGetArray",
        "VecGetLocalSize",
        "VecRestoreArray",
        "VecDestroy",
        "VecDuplicate",
        "VecNorm",
        "VecAYPX",
        "MatMult",
        "ISCreateGeneral",
        "ISDestroy",
        "KSPCreate",
        "KSPSetOperators",
        "KSPSetType",
        "KSPGetType",
        "KSPSetTolerances",
        "KSPGetTolerances",
        "KSPGetPC",
        "KSPSetFromOptions",
        "KSPSetUp",
        "KSPSolve",
        "KSPGetConvergedReason",
        "KSPGetIterationNumber",
        "KSPGetResidualNorm",
        "KSPDestroy",
        "PCSetType",
        "PCGetType",
        "PCFieldSplitSetIS",
        "mortar_petsc_comm_self",
        "mortar_petsc_thread_serialized",
    ];

    /// The include directories and the linking of the pkg-config package found first among
    /// `names`, or a panic that says what to install.
    fn probe(names: &[&str], min_version: Option<&str>) -> pkg_config::Library {
        let mut errors = Vec::new();
        for name in names {
            let mut config = pkg_config::Config::new();
            if let Some(v) = min_version {
                config.atleast_version(v);
            }
            match config.probe(name) {
                Ok(lib) => return lib,
                Err(e) => errors.push(format!("{name}: {e}")),
            }
        }
        panic!(
            "the `petsc` feature needs PETSc (>= 3.18) and its MPI, found by pkg-config \
             (on Debian: apt-get install petsc-dev libclang-dev; for another PETSc, put \
             $PETSC_DIR/$PETSC_ARCH/lib/pkgconfig on PKG_CONFIG_PATH):\n{}",
            errors.join("\n")
        );
    }

    pub fn build() {
        let petsc = probe(&["PETSc", "petsc"], Some("3.18"));
        let mpi = probe(&["mpi", "ompi-c", "mpich"], None);
        let includes: Vec<PathBuf> = petsc
            .include_paths
            .iter()
            .chain(&mpi.include_paths)
            .cloned()
            .collect();
        // Shared libraries' directories for the tests and examples to run without
        // LD_LIBRARY_PATH (PETSc from a prefix outside the loader's path).
        for dir in petsc.link_paths.iter().chain(&mpi.link_paths) {
            println!("cargo:rustc-link-arg=-Wl,-rpath,{}", dir.display());
        }

        println!("cargo:rerun-if-changed=src/shim.c");
        cc::Build::new()
            .file("src/shim.c")
            .includes(&includes)
            .warnings(true)
            .compile("mortar_petsc_shim");

        println!("cargo:rerun-if-changed=src/shim.h");
        let mut builder = bindgen::Builder::default()
            .header("src/shim.h")
            .clang_args(includes.iter().map(|p| format!("-I{}", p.display())))
            .allowlist_recursively(true)
            .allowlist_var("PETSC_DEFAULT|PETSC_VERSION_.*")
            .allowlist_type("KSPConvergedReason|PetscErrorType|PetscCopyMode|NormType")
            .constified_enum_module("KSPConvergedReason")
            .layout_tests(false)
            .generate_comments(false)
            .parse_callbacks(Box::new(bindgen::CargoCallbacks::new()));
        for f in FUNCTIONS {
            builder = builder.allowlist_function(f);
        }
        let bindings = builder
            .generate()
            .expect("bindgen could not read PETSc's headers (is libclang installed?)");
        let out = PathBuf::from(std::env::var("OUT_DIR").unwrap()).join("petsc_bindings.rs");
        bindings.write_to_file(&out).expect("writing the bindings");
    }
}
