"""SDF models that are refused or warned about: bad XML, entities, bad joints and links, unsupported parts, and a
surface the builder refuses without leaving geoms behind."""
import pytest
from sdf_helpers import box_collision, inertial, link, model, sdf

from turtle_sim_ode.models.builder import build_model
from turtle_sim_ode.models.description import GazeboSurface
from turtle_sim_ode.models.sdf import parse_sdf_model
from turtle_sim_ode.models.sdf_world import parse_sdf_world
from turtle_sim_ode.models.text import ModelError
from turtle_sim_ode.physics.world import PhysicsWorld


# --- errors -------------------------------------------------------------------------------
def test_bad_xml_reports_line():
    with pytest.raises(ModelError, match="line 4, column 2: mismatched tag"):
        parse_sdf_model('<sdf version="1.6">\n<model name="m">\n<link name="a">\n</model></sdf>')


@pytest.mark.parametrize(
    "doctype",
    [
        '<!DOCTYPE m [<!ENTITY a "aaaaaaaaaa"><!ENTITY b "&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;">'
        '<!ENTITY c "&b;&b;&b;&b;&b;&b;&b;&b;&b;&b;"><!ENTITY d "&c;&c;&c;&c;&c;&c;&c;&c;&c;&c;">]>',
        '<!DOCTYPE m [<!ENTITY d SYSTEM "file:///etc/passwd">]>',
    ],
)
def test_entities_are_refused(doctype):
    with pytest.raises(ModelError, match="XML guard"):
        parse_sdf_model(f'<?xml version="1.0"?>{doctype}<model name="m"><link name="&d;"/></model>')
    with pytest.raises(ModelError, match="XML guard"):
        parse_sdf_world(f'<?xml version="1.0"?>{doctype}<sdf version="1.6"><world name="&d;"/></sdf>')


def joint(parent, child, joint_type="revolute", extra="", name="j"):
    return (
        f'<joint name="{name}" type="{joint_type}"><parent>{parent}</parent><child>{child}</child>' f"{extra}</joint>"
    )


@pytest.mark.parametrize(
    "body, message",
    [
        (model("m", link("a"), joint("missing", "a")), "parent link 'missing' does not exist"),
        (model("m", link("a"), joint("a", "missing")), "child link 'missing' does not exist"),
        (model("m", link("a"), joint("world", "a", "fixed")), "joints to the world"),
        (model("m", link("a"), link("b"), joint("a", "b", "ball")), "unsupported type 'ball'"),
        (
            model("m", link("a"), link("b"), joint("a", "b", extra="<axis><xyz>0 0 0</xyz></axis>")),
            "axis must not be zero",
        ),
        (model("m", link("a"), link("a")), "duplicate link name 'a'"),
        (model("m", link("a"), link("b"), link("c"), joint("a", "c"), joint("b", "c", name="k")), "two parents"),
        (model("m", link("a"), link("b"), joint("a", "b"), joint("a", "b", name="j")), "duplicate joint name 'j'"),
        (model("m", link("r"), link("a"), link("b"), joint("a", "b"), joint("b", "a", name="k")), "cycle"),
        (model("m", '<link name="a"><pose relative_to="b">0 0 0 0 0 0</pose></link>'), "relative_to"),
        (model("m", '<link name="a"><pose>0 0 0</pose></link>'), "expected 6 numbers"),
        (model("m", link("a", extra="<inertial><mass>0</mass></inertial>")), "mass must be > 0"),
        (
            model("m", link("a", extra='<collision name="c"><geometry><heightmap/></geometry>' "</collision>")),
            "unsupported geometry",
        ),
        (model("m", "<include><uri>model://x</uri></include>", link("a")), "an <include> inside a model"),
        (model("m", '<model><link name="a"/></model>', link("a")), "a nested <model> needs a name"),
        (model("m"), "has no <link>"),
        (
            model("m", link("a"), link("b"), '<joint name="j" type="fixed"><parent>a</parent></joint>'),
            "needs <parent> and <child>",
        ),
        (
            model(
                "m",
                link("a"),
                link("b"),
                joint("a", "b", extra="<axis><limit><lower>1</lower><upper>0</upper></limit></axis>"),
            ),
            "lower 1.0 > upper 0.0",
        ),
        (
            model(
                "m",
                link(
                    "a", extra='<collision name="c"><geometry><plane><size>1</size></plane>' "</geometry></collision>"
                ),
                static=True,
            ),
            "expected 2 numbers",
        ),
        (
            model(
                "m",
                link(
                    "a",
                    extra='<collision name="c"><geometry><sphere><radius>-1</radius>'
                    "</sphere></geometry></collision>",
                ),
            ),
            "must be > 0",
        ),
        ('<model name="m"><static>maybe</static><link name="a"/></model>', "expected true or false"),
        ('<world name="w"/>', "world_name launch argument"),
    ],
)
def test_model_errors(body, message):
    with pytest.raises(ModelError, match=message):
        parse_sdf_model(sdf(body))


@pytest.mark.parametrize(
    "text, message",
    [
        (sdf(model("m", link("a")), "1.8"), "version 1.8 is not supported"),
        (sdf(model("m", link("a")), "one"), "expected a version"),
        (
            sdf(
                model(
                    "m", link("a"), link("b"), joint("a", "b", extra='<axis><xyz expressed_in="f">1 0 0</xyz></axis>')
                ),
                "1.7",
            ),
            "expressed_in='f'",
        ),
        ('<robot name="r"/>', "root element"),
        (sdf(model("m", link("a")) + model("n", link("a"))), "expected one <model>"),
    ],
)
def test_document_errors(text, message):
    with pytest.raises(ModelError, match=message):
        parse_sdf_model(text)


def test_unsupported_parts_are_warned_about():
    surface = "<surface><friction><ode><mu>{}</mu></ode></friction></surface>"
    robot = parse_sdf_model(
        sdf(
            model(
                "m",
                "<self_collide>true</self_collide>",
                link(
                    "a",
                    extra=inertial()
                    + "<kinematic>true</kinematic>"
                    + box_collision("1 1 1", surface.format(0.5))
                    + box_collision("1 1 1", surface.format(0.7)),
                ),
                link("b"),
                joint("a", "b", extra="<axis><dynamics><spring_stiffness>5</spring_stiffness>" "</dynamics></axis>"),
            )
        )
    )
    assert robot.surfaces["a"].mu1 == 0.7
    for expected in (
        "<kinematic> is not supported",
        "different <surface> values",
        "<spring_stiffness> is not supported",
        "<self_collide> is not applied",
    ):
        assert any(expected in w for w in robot.warnings), expected


def test_bad_surface_leaves_the_static_space_clean():
    physics = PhysicsWorld()
    text = sdf(
        model(
            "m",
            link(
                "a",
                extra=box_collision("1 1 1")
                + box_collision("1 1 1", "<surface><friction><ode><mu>-1</mu></ode></friction></surface>"),
            ),
            static=True,
        )
    )
    with pytest.raises(ModelError, match=r"link 'a'.*friction/ode/mu"):  # the parser refuses it (issue 14)
        parse_sdf_model(text)
    robot = parse_sdf_model(text.replace("<mu>-1</mu>", "<mu>1</mu>"))
    robot.surfaces["a"] = GazeboSurface(mu1=-1.0)  # past the parser: the builder must still clean up
    with pytest.raises(ValueError, match="mu"):
        build_model(physics, robot)
    assert physics.static_space.getNumGeoms() == 0
