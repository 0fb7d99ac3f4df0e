// The implementations of the header-only parsers the core's readers use (core/src/io), compiled
// into the wasm build only: natively they come from Debian's libtinygltf and libtinyobjloader.
// Images are never decoded (the readers keep their bytes as they are), so stb_image is left out;
// TINYGLTF_NO_STB_IMAGE and TINYGLTF_NO_STB_IMAGE_WRITE are set for every io source (io.cmake).
#define TINYGLTF_IMPLEMENTATION
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_gltf.h>
#include <tiny_obj_loader.h>
