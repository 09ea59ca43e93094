# turtlebot_gazebo's world for turtlebot_world.launch, unless the user has chosen one (as upstream's hook does,
# with the path written in at build time instead of a rospack call each time a shell sources the workspace).
@[if DEVELSPACE]@
: ${TURTLEBOT_GAZEBO_WORLD_FILE:=@(CMAKE_CURRENT_SOURCE_DIR)/worlds/playground.world}
@[else]@
: ${TURTLEBOT_GAZEBO_WORLD_FILE:=$CATKIN_ENV_HOOK_WORKSPACE/share/turtlebot_gazebo/worlds/playground.world}
@[end if]@
export TURTLEBOT_GAZEBO_WORLD_FILE
