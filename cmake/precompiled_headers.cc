// The one translation unit of the targets that build the precompiled
// headers (cmake/precompiled_headers.cmake): the header is compiled before
// it; it has nothing of its own.
