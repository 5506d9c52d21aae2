// TetGen's error exit, replaced.
//
// TetGen 1.5.0 (Debian's libtet1.5) reports every error by calling terminatetetgen(mesh, code),
// which, built with TETLIBRARY, calls mesh->freememory() and throws the code. The mesh is a
// local object of tetrahedralize(), whose destructor calls freememory() again while the
// exception unwinds, and freememory() does not reset what it deleted: every TetGen error (a
// self-intersecting surface, for one) ends in a double free and a crash.
//
// terminatetetgen() is an inline function of tetgen.h that libtet keeps as a weak, exported
// symbol and calls only through its PLT (43 call sites, none inlined), so this strong
// definition, in a library that the dynamic linker searches before libtet (SPTMeshing links
// libtet), takes its place: it only throws, and the destructor frees the mesh once. The test
// TestTetGenMesherErrors meshes a self-intersecting surface and would crash without it.
//
// tetgen.h is deliberately not included here: it defines the inline version.

class tetgenmesh;

__attribute__((visibility("default"))) void terminatetetgen(tetgenmesh*, int code);

void terminatetetgen(tetgenmesh*, int code)
{
  throw code;
}
