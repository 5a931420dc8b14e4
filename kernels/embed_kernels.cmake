# Turns OpenCL kernel files into one C++ source with each file's text as a raw
# string literal (thesis A.4: kernels live in their own files but travel inside
# the binary). Runs at build time: cmake -DOUT=<cpp> -DFILES=<a.cl|b.cl> -P this.
string(REPLACE "|" ";" FILES "${FILES}")
set(body "// Generated from kernels/*.cl by kernels/embed_kernels.cmake; do not edit.\n")
string(APPEND body "#include \"pipeline/opencl/embedded_kernels.h\"\n\nnamespace dv {\nnamespace {\n")
string(APPEND body "const EmbeddedKernel kKernels[] = {\n")
set(count 0)
foreach(f ${FILES})
  get_filename_component(name ${f} NAME)
  file(READ ${f} text)
  # A raw string literal cannot hold its own closing delimiter; kernels never do.
  string(APPEND body "  {\"${name}\", R\"dvcl(${text})dvcl\"},\n")
  math(EXPR count "${count} + 1")
endforeach()
string(APPEND body "};\n}  // namespace\n\n")
string(APPEND body "const EmbeddedKernel* embeddedKernels() { return kKernels; }\n")
string(APPEND body "int embeddedKernelCount() { return ${count}; }\n\n}  // namespace dv\n")
file(WRITE ${OUT}.tmp "${body}")
# Only touch the output when it changed, so unchanged kernels cause no rebuild.
execute_process(COMMAND ${CMAKE_COMMAND} -E copy_if_different ${OUT}.tmp ${OUT})
file(REMOVE ${OUT}.tmp)
