//! Schedule ordering and errors, deferred commands between systems, and App stepping.

use std::sync::{Arc, Mutex};

use engine::ecs::{Entity, EventReader, Events, World};
use engine::schedule::{App, AppError, Schedule, ScheduleError, Time};

/// A shared log the test systems append their names to.
#[derive(Clone, Default)]
struct Log(Arc<Mutex<Vec<String>>>);

impl Log {
    fn system(&self, name: &'static str) -> impl FnMut(&mut World) + Send + 'static {
        let log = self.clone();
        move |_: &mut World| log.0.lock().unwrap().push(name.to_owned())
    }
    fn take(&self) -> Vec<String> {
        std::mem::take(&mut self.0.lock().unwrap())
    }
}

fn noop(_: &mut World) {}

#[test]
fn ties_are_broken_by_insertion_order() {
    let mut schedule = Schedule::new();
    for name in ["c", "a", "b"] {
        schedule.add_system(name, noop);
    }
    schedule.build().unwrap();
    assert_eq!(schedule.order(), vec!["c", "a", "b"]);
}

#[test]
fn constraints_and_sets_order_systems() {
    let log = Log::default();
    let mut schedule = Schedule::new();
    schedule
        .add_system("render", log.system("render"))
        .after("character");
    schedule
        .add_system("gait", log.system("gait"))
        .in_set("character");
    schedule
        .add_system("ik", log.system("ik"))
        .in_set("character")
        .after("gait");
    schedule.add_system("input", log.system("input"));
    schedule
        .add_system("raycast", log.system("raycast"))
        .before("ik")
        .after("gait");
    schedule.configure_set("character").after("input");
    schedule.build().unwrap();
    let expected = vec!["input", "gait", "raycast", "ik", "render"];
    assert_eq!(schedule.order(), expected);
    schedule.run(&mut World::new()).unwrap();
    assert_eq!(log.take(), expected);
    let printed = schedule.to_string();
    assert_eq!(
        printed,
        "  1. input\n  2. gait\n  3. raycast\n  4. ik\n  5. render\n"
    );
}

#[test]
fn cycle_error_names_the_systems() {
    let mut schedule = Schedule::new();
    schedule.add_system("free", noop);
    schedule.add_system("gait", noop).after("balance");
    schedule.add_system("ik", noop).after("gait");
    schedule.add_system("balance", noop).after("ik");
    let error = schedule.build().unwrap_err();
    assert_eq!(
        error,
        ScheduleError::Cycle {
            systems: vec!["gait".into(), "ik".into(), "balance".into()]
        }
    );
    assert_eq!(
        error.to_string(),
        "ordering constraints form a cycle: gait -> ik -> balance -> gait"
    );
    assert!(schedule.run(&mut World::new()).is_err());
}

#[test]
fn cycle_through_a_set_is_found() {
    let mut schedule = Schedule::new();
    schedule.add_system("a", noop).in_set("s");
    schedule.add_system("b", noop).before("s");
    schedule.configure_set("s").before("b");
    let ScheduleError::Cycle { systems } = schedule.build().unwrap_err() else {
        panic!("expected a cycle");
    };
    assert_eq!(systems, vec!["a", "b"]);
}

#[test]
fn unknown_label_and_duplicate_name() {
    let mut schedule = Schedule::new();
    schedule.add_system("gait", noop).after("inptu");
    let error = schedule.build().unwrap_err();
    assert_eq!(
        error,
        ScheduleError::UnknownLabel {
            system: "gait".into(),
            label: "inptu".into()
        }
    );
    assert!(
        error
            .to_string()
            .contains("`gait` is ordered relative to `inptu`")
    );

    let mut schedule = Schedule::new();
    schedule.configure_set("character").before("nowhere");
    assert_eq!(
        schedule.build().unwrap_err(),
        ScheduleError::UnknownLabel {
            system: "set character".into(),
            label: "nowhere".into()
        }
    );

    let mut schedule = Schedule::new();
    schedule.add_system("gait", noop);
    schedule.add_system(String::from("gait"), noop);
    assert_eq!(
        schedule.build().unwrap_err(),
        ScheduleError::DuplicateName("gait".into())
    );
}

#[test]
fn replace_keeps_position_and_remove_drops_constraints() {
    let log = Log::default();
    let mut schedule = Schedule::new();
    schedule
        .add_system("carve", log.system("carve"))
        .after("grass_deform");
    schedule
        .add_system("grass_deform", log.system("grass_deform"))
        .after("refit");
    schedule.add_system("refit", log.system("refit"));
    schedule.run(&mut World::new()).unwrap();
    assert_eq!(log.take(), vec!["refit", "grass_deform", "carve"]);

    schedule
        .replace("grass_deform", log.system("my_grass"))
        .unwrap();
    schedule.run(&mut World::new()).unwrap();
    assert_eq!(log.take(), vec!["refit", "my_grass", "carve"]);
    assert_eq!(
        schedule.replace("nope", noop),
        Err(ScheduleError::UnknownSystem("nope".into()))
    );

    schedule.remove("grass_deform").unwrap();
    assert!(!schedule.contains("grass_deform"));
    schedule.run(&mut World::new()).unwrap();
    assert_eq!(
        log.take(),
        vec!["carve", "refit"],
        "constraints naming it are gone"
    );
    assert_eq!(
        schedule.remove("grass_deform"),
        Err(ScheduleError::UnknownSystem("grass_deform".into()))
    );

    // Adding after a build re-resolves.
    schedule
        .add_system("first", log.system("first"))
        .before("carve");
    assert!(!schedule.is_built());
    schedule.run(&mut World::new()).unwrap();
    assert_eq!(
        log.take(),
        vec!["refit", "first", "carve"],
        "ready systems by insertion order"
    );
}

#[test]
fn removing_a_system_keeps_set_labels() {
    let mut schedule = Schedule::new();
    schedule.add_system("late", noop).after("io");
    schedule.add_system("io", noop).in_set("io");
    schedule.add_system("reader", noop).in_set("io");
    schedule.remove("io").unwrap();
    schedule.build().unwrap();
    assert_eq!(
        schedule.order(),
        vec!["reader", "late"],
        "`io` still names the set"
    );
}

#[test]
fn commands_are_applied_after_each_system() {
    struct Counted(usize);
    let mut schedule = Schedule::new();
    schedule.add_system("spawner", |world: &mut World| {
        world.commands().spawn((1u8,));
        world.commands().spawn((2u8,));
        assert_eq!(world.query::<&u8>().iter().count(), 0, "deferred");
    });
    schedule.add_system("counter", |world: &mut World| {
        let n = world.query::<&u8>().iter().count();
        world.insert_resource(Counted(n));
    });
    let mut world = World::new();
    schedule.run(&mut world).unwrap();
    assert_eq!(
        world.resource::<Counted>().0,
        2,
        "the next system sees the spawns"
    );
}

#[test]
fn failing_commands_are_reported_with_the_system() {
    let mut world = World::new();
    let gone = world.spawn((1u8,));
    world.despawn(gone).unwrap();
    let mut schedule = Schedule::new();
    schedule.add_system("despawner", move |world: &mut World| {
        world.commands().despawn(gone)
    });
    schedule.add_system("after", |world: &mut World| {
        world.insert_resource(5u32);
    });
    let error = schedule.run(&mut world).unwrap_err();
    let ScheduleError::Commands { system, source } = &error else {
        panic!("expected a commands error, got {error}");
    };
    assert_eq!(system, "despawner");
    assert_eq!(source.failures.len(), 1);
    assert!(
        error.to_string().contains("system `despawner` failed"),
        "{error}"
    );
    assert!(
        !world.contains_resource::<u32>(),
        "the step stops at the failure"
    );
}

#[test]
fn app_validates_dt() {
    for dt in [0.0, -0.1, 1.5, f32::NAN, f32::INFINITY] {
        match App::new(dt) {
            Err(AppError::InvalidDt(_)) => {}
            _ => panic!("dt {dt} accepted"),
        }
    }
    let error = App::new(2.0).err().unwrap();
    assert_eq!(
        error.to_string(),
        "time step dt must be finite, > 0 and <= 1 s; got 2"
    );
    assert!(App::new(1.0).is_ok());
    let mut app = App::new(0.1).unwrap();
    assert_eq!(app.run_for(-1.0), Err(AppError::InvalidDuration(-1.0)));
    assert!(app.run_for(f64::NAN).is_err());
}

#[test]
fn app_time_steps_without_drift() {
    #[derive(Default)]
    struct Seen(Vec<(u64, f64)>);
    let mut app = App::new(1.0 / 60.0).unwrap();
    app.world.insert_resource(Seen::default());
    app.add_system("watch", |world: &mut World| {
        let time = *world.resource::<Time>();
        world
            .resource_mut::<Seen>()
            .0
            .push((time.step, time.elapsed));
    });
    app.run_steps(3).unwrap();
    app.step().unwrap();
    let dt = f64::from(1.0f32 / 60.0);
    {
        let seen = &app.world.resource::<Seen>().0;
        let steps: Vec<u64> = seen.iter().map(|s| s.0).collect();
        assert_eq!(steps, vec![0, 1, 2, 3]);
        assert_eq!(seen[3].1, 3.0 * dt);
    }
    app.run_for(100.0).unwrap();
    let time = *app.world.resource::<Time>();
    assert_eq!(time.step, 6004);
    assert_eq!(app.steps_done(), 6004);
    assert_eq!(time.elapsed, 6004.0 * dt, "elapsed is step * dt exactly");
}

#[test]
fn app_updates_events_each_step() {
    struct Ping(u64);
    #[derive(Default)]
    struct Heard(Vec<(u64, u64)>, EventReader);
    let mut app = App::new(0.5).unwrap();
    app.world.add_event::<Ping>();
    app.world.insert_resource(Heard::default());
    app.add_system("reader", |world: &mut World| {
        let step = world.resource::<Time>().step;
        let events = world.resource::<Events<Ping>>();
        let mut heard = world.resource_mut::<Heard>();
        let Heard(log, reader) = &mut *heard;
        log.extend(reader.read(&events).map(|p| (step, p.0)));
    })
    .after("sender");
    app.add_system("sender", |world: &mut World| {
        let step = world.resource::<Time>().step;
        if step == 0 {
            world.send_event(Ping(step));
        }
    });
    app.run_steps(3).unwrap();
    assert_eq!(app.world.resource::<Heard>().0, vec![(0, 0)]);
    assert!(
        app.world.resource::<Events<Ping>>().is_empty(),
        "dropped two updates later"
    );
}

#[test]
fn app_runs_the_same_twice() {
    fn run() -> Vec<(Entity, f32)> {
        let mut app = App::new(0.25).unwrap();
        app.world.spawn_batch((0..5).map(|i| (i as f32,)));
        app.add_system("grow", |world: &mut World| {
            let dt = world.resource::<Time>().dt;
            for x in world.query_mut::<&mut f32>() {
                *x = (*x + dt).sqrt();
            }
        });
        app.run_steps(10).unwrap();
        app.world
            .query::<(Entity, &f32)>()
            .iter()
            .map(|(e, x)| (e, *x))
            .collect()
    }
    assert_eq!(run(), run());
}

/// The tutorial of `docs/parts/ecs.md`, kept compiling and running.
#[test]
fn tutorial_example_runs() -> Result<(), Box<dyn std::error::Error>> {
    use engine::ecs::{PreparedQuery, With};

    struct Position(glam::Vec3);
    struct Velocity(glam::Vec3);
    struct Player;

    let mut app = App::new(1.0 / 60.0)?;
    let player = app.world.spawn((
        Position(glam::Vec3::ZERO),
        Velocity(glam::Vec3::NEG_Y * 30.0),
        Player,
    ));

    let mut moving = PreparedQuery::<(&mut Position, &Velocity)>::new();
    app.add_system("integrate", move |world: &mut World| {
        let dt = world.resource::<Time>().dt;
        for (p, v) in moving.query_mut(world) {
            p.0 += v.0 * dt;
        }
    });
    app.add_system("fall_out", |world: &mut World| {
        for (e, p) in world
            .query_filtered::<(Entity, &Position), With<Player>>()
            .iter()
        {
            if p.0.y < -10.0 {
                world.commands().despawn(e);
            }
        }
    })
    .after("integrate");
    app.run_for(1.0)?;
    assert!(
        !app.world.contains(player),
        "fell below -10 m within a second"
    );
    app.schedule.replace("fall_out", |_: &mut World| {})?;
    assert_eq!(app.schedule.order(), vec!["integrate", "fall_out"]);
    Ok(())
}
