"""Small scenes built in Python for the tests."""
import stiffsoft


def ball_on_box(duration=0.1, integrator="backward_euler"):
    """A soft ball dropped on an affine box resting on a fixed ground (as examples/embed)."""
    scene = stiffsoft.Scene(name="ball_on_box", description="test: a soft ball on an affine box")
    scene.time.dt = 0.01
    scene.time.duration = duration
    scene.time.integrator = integrator
    scene.contact.mu = 0.3
    scene.contact.dhat = 0.0005
    scene.bodies.append(stiffsoft.Body(name="ground", kind="fixed", shape=stiffsoft.Shape.box((2.0, 0.1, 2.0)),
                                       position=(0, -0.05, 0)))
    scene.bodies.append(stiffsoft.Body(name="box", shape=stiffsoft.Shape.box((0.4, 0.2, 0.4)),
                                       position=(0, 0.101, 0), density=800))
    scene.bodies.append(stiffsoft.Body(name="ball", model="soft", shape=stiffsoft.Shape.sphere(0.1),
                                       position=(0.02, 0.35, 0), mesh_size=0.05, density=1100,
                                       material=stiffsoft.Material(young=2e5, poisson=0.45)))
    return scene
