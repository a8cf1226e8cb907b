# The CUDA backend (src/penumbra/backends/cuda). PENUMBRA_ENABLE_CUDA=AUTO (the
# default) builds it whenever nvcc is found (on PATH, CUDACXX or
# /usr/local/cuda), ON requires it, OFF leaves it out. Device code is compiled
# for sm_90 (H100/H200) plus compute_90 PTX, which newer GPUs JIT; override
# with -DCMAKE_CUDA_ARCHITECTURES or CMake's CUDAARCHS environment variable
# (.ci/run sets 90-virtual on a machine without a GPU: PTX only, the device
# code's compile check without assembling it). Every CUDA unit samples all voxel types
# through one switch, so each Lighting compiles once (compile time: CI).
set(PENUMBRA_ENABLE_CUDA AUTO CACHE STRING "Build the CUDA backend: AUTO (when nvcc is found), ON or OFF")
set_property(CACHE PENUMBRA_ENABLE_CUDA PROPERTY STRINGS AUTO ON OFF)

set(PENUMBRA_CUDA FALSE)
if(NOT PENUMBRA_ENABLE_CUDA STREQUAL "OFF")
  if(NOT CMAKE_CUDA_COMPILER AND NOT DEFINED ENV{CUDACXX} AND EXISTS /usr/local/cuda/bin/nvcc)
    set(CMAKE_CUDA_COMPILER /usr/local/cuda/bin/nvcc)
  endif()
  include(CheckLanguage)
  check_language(CUDA)
  if(CMAKE_CUDA_COMPILER)
    if(NOT DEFINED CMAKE_CUDA_ARCHITECTURES AND NOT DEFINED ENV{CUDAARCHS})
      set(CMAKE_CUDA_ARCHITECTURES 90)
    endif()
    enable_language(CUDA)
    # CMake 3.25 knows nvcc up to C++17; nvcc 13 takes C++20 (the targets'
    # CXX_STANDARD 20 applies to their CUDA sources too).
    set(CMAKE_CUDA20_STANDARD_COMPILE_OPTION "-std=c++20")
    set(CMAKE_CUDA20_EXTENSION_COMPILE_OPTION "-std=c++20")
    find_package(CUDAToolkit REQUIRED)
    set(PENUMBRA_CUDA TRUE)
    message(STATUS "penumbra: CUDA backend on (${CMAKE_CUDA_COMPILER}, architectures ${CMAKE_CUDA_ARCHITECTURES})")
  elseif(PENUMBRA_ENABLE_CUDA STREQUAL "ON")
    message(FATAL_ERROR "PENUMBRA_ENABLE_CUDA=ON but no CUDA compiler (nvcc) was found; set CUDACXX")
  else()
    message(STATUS "penumbra: CUDA backend off (no nvcc found)")
  endif()
endif()

# What every user of penumbra::core sees: the backend's definition and runtime.
function(penumbra_cuda_definitions target)
  if(PENUMBRA_CUDA)
    target_compile_definitions(${target} PUBLIC PENUMBRA_HAVE_CUDA)
    target_link_libraries(${target} PUBLIC CUDA::cudart_static)
  endif()
endfunction()

# penumbra_cuda_sources(<library> <source>...): .cu units of <library>, only
# in builds with the backend.
function(penumbra_cuda_sources library)
  if(NOT PENUMBRA_CUDA)
    return()
  endif()
  foreach(source IN LISTS ARGN)
    set_source_files_properties(${source} TARGET_DIRECTORY ${library} PROPERTIES COMPILE_OPTIONS
      "--expt-relaxed-constexpr;--extended-lambda;-O3;-Xcompiler=-O3;--diag-suppress=20012,20013,20014,20015")
  endforeach()
  target_sources(${library} PRIVATE ${ARGN})
endfunction()
