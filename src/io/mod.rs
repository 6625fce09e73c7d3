//! File input and output: Gmsh 4.1 meshes in, Matrix Market and JSON out.
