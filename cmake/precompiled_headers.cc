// The one translation unit of the target that builds the precompiled
// header (cmake/precompiled_headers.cmake): the header is compiled before
// it; it has nothing of its own.
