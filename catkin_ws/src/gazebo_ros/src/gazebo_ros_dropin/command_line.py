"""ROS-free reading of Gazebo classic's server and client command lines (gzserver, gazebo, gzclient), as
gazebo_ros's scripts pass them on: what the simulator does with each option, and what it says about the rest.

Options and their spellings are gazebo-classic's (gazebo/Server.cc, Server::ParseArgs; gazebo/gui/main.cc for
the client's -g): a world file as the first positional argument (default worlds/empty.world), -u/--pause,
-e/--physics ENGINE, -s/--server-plugin LIB (repeatable), -g/--gui-plugin LIB, --verbose, -r/--record and the
other --record* options, --seed, --iters, --lockstep, --minimal_comms, -o/--profile, -p/--play.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import List, Optional, Sequence

# The world gzserver loads when none is named (Server::ParseArgs).
DEFAULT_WORLD = "worlds/empty.world"
# Plugins gazebo_ros's scripts add to every command line: this simulator has their function built in.
BUILT_IN_PLUGINS = ("libgazebo_ros_api_plugin.so", "libgazebo_ros_paths_plugin.so")
# Options that take a value, with their long names (the short ones map to these).
VALUE_OPTIONS = {
    "-e": "--physics",
    "--physics": "--physics",
    "-s": "--server-plugin",
    "--server-plugin": "--server-plugin",
    "-g": "--gui-plugin",
    "--gui-plugin": "--gui-plugin",
    "-p": "--play",
    "--play": "--play",
    "-o": "--profile",
    "--profile": "--profile",
    "--seed": "--seed",
    "--iters": "--iters",
    "--record_encoding": "--record_encoding",
    "--record_path": "--record_path",
    "--record_period": "--record_period",
    "--record_filter": "--record_filter",
    "--server-logfile": "--server-logfile",
}
FLAG_OPTIONS = {
    "-u": "--pause",
    "--pause": "--pause",
    "--verbose": "--verbose",
    "-r": "--record",
    "--record": "--record",
    "--record_resources": "--record_resources",
    "--lockstep": "--lockstep",
    "--minimal_comms": "--minimal_comms",
    "-v": "--version",
    "--version": "--version",
    "-h": "--help",
    "--help": "--help",
}
# Options accepted with a note that they change nothing here.
IGNORED = {
    "--seed": "the simulation has no random numbers to seed",
    "--iters": "the simulation runs until it is stopped",
    "--lockstep": "sensors are always stepped with the physics",
    "--minimal_comms": "there is no Gazebo transport",
    "--profile": "there are no physics profiles: the world's <physics> is used",
    "--server-logfile": "log messages go to ROS's log",
}
USAGE = """{program} -- the gazebo_ros drop-in's {what} (turtle_sim_ode, node /gazebo)

`{program}` [options] <world_file>

Options:
  -v [ --version ]           Output version information.
  --verbose                  Increase the messages written to the terminal.
  -h [ --help ]              Produce this help message.
  -u [ --pause ]             Start the server in a paused state.
  -e [ --physics ] arg       Specify a physics engine (only ode here).
  -s [ --server-plugin ] arg Load a plugin (named in a warning: not loaded).
  -g [ --gui-plugin ] arg    Load a GUI plugin (named in a warning: not loaded).
  -r [ --record ]            Record state data (refused: no Gazebo state log).
"""


class CommandLineError(ValueError):
    """An option this simulator refuses, or one given without its value: the message says which and why."""


@dataclass
class ServerOptions:
    """What a gzserver/gazebo command line asks of the simulator."""

    world: str = DEFAULT_WORLD
    paused: bool = False
    verbose: bool = False
    physics: str = "ode"
    plugins: List[str] = field(default_factory=list)
    gui_plugins: List[str] = field(default_factory=list)
    help: bool = False
    version: bool = False
    notes: List[str] = field(default_factory=list)  # one warning each: accepted options with no effect here
    extra: List[str] = field(default_factory=list)  # positional arguments after the world (passed to plugins)


def split_ros_arguments(argv: Sequence[str]) -> List[str]:
    """The arguments without ROS remappings (``__name:=x``, ``a:=b``), as libcommon.sh's relocate_remappings
    sets them apart."""
    return [arg for arg in argv if ":=" not in arg]


def parse_server_args(argv: Sequence[str]) -> ServerOptions:
    """Read a gzserver command line (without the program name and without ROS remappings).

    CommandLineError for --record and the other recording options, --play, an unknown option or a missing
    value; Gazebo's own parser lets unknown options pass (allow_unregistered), here they are a note."""
    options = ServerOptions()
    positional: List[str] = []
    args = list(argv)
    index = 0
    while index < len(args):
        arg = args[index]
        index += 1
        name, equals, inline = arg.partition("=") if arg.startswith("--") else (arg, "", "")
        if name in VALUE_OPTIONS:
            option = VALUE_OPTIONS[name]
            if equals:
                value = inline
            elif index < len(args):
                value = args[index]
                index += 1
            else:
                raise CommandLineError("option %s needs a value" % name)
            _take_value(options, option, value)
        elif arg in FLAG_OPTIONS:
            _take_flag(options, FLAG_OPTIONS[arg])
        elif arg.startswith("-") and arg != "-":
            options.notes.append("unknown option %s ignored (gzserver passes it to system plugins)" % arg)
        else:
            positional.append(arg)
    if positional:
        options.world = positional[0]
        options.extra = positional[1:]
    return options


def _take_flag(options: ServerOptions, option: str) -> None:
    if option == "--pause":
        options.paused = True
    elif option == "--verbose":
        options.verbose = True
    elif option == "--help":
        options.help = True
    elif option == "--version":
        options.version = True
    elif option in ("--record", "--record_resources"):
        raise CommandLineError(
            "%s: this simulator writes no Gazebo state log; record its topics with rosbag instead "
            "(rosbag record -a)" % option
        )
    else:
        options.notes.append("%s accepted, no effect: %s" % (option, IGNORED[option]))


def _take_value(options: ServerOptions, option: str, value: str) -> None:
    if option == "--physics":
        options.physics = value
        if value != "ode":
            options.notes.append("physics engine [%s] is not available: the simulator is always ODE" % value)
    elif option == "--server-plugin":
        options.plugins.append(value)
        if not value.endswith(BUILT_IN_PLUGINS):
            options.notes.append("server plugin [%s] not loaded: Gazebo plugins cannot run here" % value)
    elif option == "--gui-plugin":
        options.gui_plugins.append(value)
        if not value.endswith(BUILT_IN_PLUGINS):
            options.notes.append("GUI plugin [%s] not loaded: Gazebo plugins cannot run here" % value)
    elif option.startswith("--record"):
        raise CommandLineError(
            "%s %s: this simulator writes no Gazebo state log; record its topics with rosbag instead "
            "(rosbag record -a)" % (option, value)
        )
    elif option == "--play":
        raise CommandLineError("--play %s: this simulator cannot play Gazebo state logs" % value)
    else:
        options.notes.append("%s %s accepted, no effect: %s" % (option, value, IGNORED[option]))


def usage(program: str, what: str) -> str:
    return USAGE.format(program=program, what=what)


def node_params(options: ServerOptions, resolved_world: Optional[str]) -> dict:
    """The simulator node's private parameters for these options (the world already resolved to a file)."""
    params = {"paused": options.paused}
    if resolved_world is not None:
        params["world_name"] = resolved_world
    return params
