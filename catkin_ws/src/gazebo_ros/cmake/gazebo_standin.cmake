# find_package(gazebo) where Gazebo is not installed (Debian 12): writes gazebo's CMake package as turtle_sim_ode's
# stand-in into the devel space (on CMAKE_PREFIX_PATH of the packages configured after this one) and installs it.
# Where a real Gazebo's package config exists, nothing is written and a stand-in left from an earlier build goes.

# Gazebo 11, as Noetic's (Ubuntu 20.04) Gazebo, the last Gazebo Classic release
set(GAZEBO_STANDIN_VERSION 11.15.1)
set(GAZEBO_STANDIN_MAJOR 11)
set(GAZEBO_STANDIN_MARKER "turtle_sim_ode's stand-in")

# The first gazebo-config.cmake below the prefixes find_package searches that is not a stand-in (of this or another
# workspace), or "" in out_var.
function(find_real_gazebo_config out_var)
  set(${out_var} "" PARENT_SCOPE)
  foreach(prefix ${CMAKE_PREFIX_PATH} ${CMAKE_SYSTEM_PREFIX_PATH})
    foreach(folder lib/${CMAKE_LIBRARY_ARCHITECTURE}/cmake/gazebo lib/cmake/gazebo share/gazebo/cmake)
      foreach(name gazebo-config.cmake gazeboConfig.cmake)
        set(config "${prefix}/${folder}/${name}")
        if(EXISTS "${config}")
          file(STRINGS "${config}" marker REGEX "${GAZEBO_STANDIN_MARKER}")
          if(NOT marker)
            set(${out_var} "${config}" PARENT_SCOPE)
            return()
          endif()
        endif()
      endforeach()
    endforeach()
  endforeach()
endfunction()

find_real_gazebo_config(real_gazebo_config)
set(standin_dir "${CATKIN_DEVEL_PREFIX}/share/gazebo/cmake")
if(real_gazebo_config)
  message(STATUS "${PROJECT_NAME}: Gazebo's own CMake package (${real_gazebo_config}) is used, no stand-in written")
  file(REMOVE_RECURSE "${CATKIN_DEVEL_PREFIX}/share/gazebo")
else()
  # turtle_sim_ode's sources beside this package come first: in a fresh workspace it is not on PYTHONPATH yet
  execute_process(
    COMMAND "${PYTHON_EXECUTABLE}" "${CMAKE_CURRENT_LIST_DIR}/simulated_plugins.py"
            "${CMAKE_CURRENT_LIST_DIR}/../../turtle_sim_ode/src"
    OUTPUT_VARIABLE GAZEBO_STANDIN_SIMULATED_PLUGINS ERROR_VARIABLE simulated_plugins_error)
  # read again when a plugin is added to turtle_sim_ode (each is a line in one of these catalogues)
  foreach(catalogue world/plugins/__init__.py sensors/plugins/__init__.py)
    set(catalogue "${CMAKE_CURRENT_LIST_DIR}/../../turtle_sim_ode/src/turtle_sim_ode/${catalogue}")
    if(EXISTS "${catalogue}")
      set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS "${catalogue}")
    endif()
  endforeach()
  if(NOT GAZEBO_STANDIN_SIMULATED_PLUGINS)
    message(WARNING "${PROJECT_NAME}: ${simulated_plugins_error}the gazebo stand-in cannot tell which Gazebo plugins "
                    "turtle_sim_ode simulates")
  endif()
  foreach(name gazebo-config.cmake gazebo-config-version.cmake gazebo-standin-plugins.cmake)
    configure_file("${CMAKE_CURRENT_LIST_DIR}/${name}.in" "${standin_dir}/${name}" @ONLY)
  endforeach()
  # generated, so outside the package's source
  #catkin_lint: ignore_once external_directory
  install(DIRECTORY "${standin_dir}/" DESTINATION share/gazebo/cmake)
endif()
