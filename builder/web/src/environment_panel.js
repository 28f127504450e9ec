// The Environment tab: the project's seed, the ground, soft collision avoidance, solid
// obstacles (OBJ files), attraction points, each with its parameters, and a physiology
// season (physiology_panel.js).
import { h, render, field, numberInput, vectorInput, checkbox } from './ui.js';
import { physiologySection } from './physiology_panel.js';

/** Lines of "x y z" (or "x, y, z") as points; throws naming the line that is not three numbers. */
export function parsePoints(text) {
  const points = [];
  text.split('\n').forEach((line, i) => {
    const t = line.trim();
    if (!t) return;
    const v = t.split(/[\s,]+/).map(Number);
    if (v.length !== 3 || v.some((x) => !Number.isFinite(x))) {
      throw new Error(`attraction points, line ${i + 1}: '${t}' is not three numbers x y z`);
    }
    points.push(v);
  });
  return points;
}

export class EnvironmentPanel {
  constructor(app, container) {
    this.app = app;
    this.container = container;
  }

  render() {
    const p = this.app.project;
    const edited = () => this.app.edited();
    const set = (obj, key) => (v) => {
      obj[key] = v;
      edited();
    };
    const cone = (values, index) => (v) => {
      values[index] = v;
      edited();
    };

    const files = h(
      'textarea',
      {
        rows: 3,
        name: 'obstacle-files',
        placeholder: 'wall.obj\nshed/roof.obj',
        spellcheck: false,
      },
      p.obstacles.files.join('\n'),
    );
    files.addEventListener('change', () => {
      p.obstacles.files = files.value
        .split('\n')
        .map((s) => s.trim())
        .filter(Boolean);
      edited();
    });
    const points = h(
      'textarea',
      { rows: 3, name: 'attraction-points', placeholder: '0 0 1.2\n0.5 0 1.2', spellcheck: false },
      p.attraction.points.map((q) => q.join(' ')).join('\n'),
    );
    const pointsError = h('p', { class: 'error-text', hidden: true });
    points.addEventListener('change', () => {
      try {
        p.attraction.points = parsePoints(points.value);
        pointsError.hidden = true;
        edited();
      } catch (e) {
        pointsError.textContent = e.message;
        pointsError.hidden = false;
      }
    });
    const attractionFile = h('input', {
      type: 'text',
      name: 'attraction-file',
      value: p.attraction.file,
      placeholder: 'points.csv',
    });
    attractionFile.addEventListener('change', () => {
      p.attraction.file = attractionFile.value.trim();
      edited();
    });

    render(
      this.container,
      h(
        'section',
        { class: 'group' },
        h('h2', {}, 'Project'),
        h(
          'div',
          { class: 'grid2' },
          field(
            'Seed',
            numberInput(p.seed, set(p, 'seed'), { min: 0, integer: true, name: 'project-seed' }),
            { title: 'the seed of every block that has none of its own' },
          ),
          field(
            'Mesh detail',
            numberInput(p.mesh_detail, set(p, 'mesh_detail'), {
              min: 0.1,
              max: 4,
              step: 0.1,
              name: 'mesh-detail',
            }),
            { title: "a factor on every organ's mesh resolution, 0.1 to 4" },
          ),
        ),
      ),
      h(
        'section',
        { class: 'group' },
        h(
          'h2',
          {},
          h(
            'label',
            { class: 'toggle' },
            checkbox(p.ground.enabled, set(p.ground, 'enabled'), { name: 'ground' }),
            'Ground',
          ),
        ),
        h(
          'div',
          { class: 'grid2' },
          field(
            'Size x, y',
            vectorInput(p.ground.size, set(p.ground, 'size'), {
              min: 0.01,
              step: 0.5,
              name: 'ground-size',
            }),
            { unit: 'm' },
          ),
          field(
            'Centre x, y',
            vectorInput(p.ground.center, set(p.ground, 'center'), {
              step: 0.5,
              name: 'ground-center',
            }),
            { unit: 'm' },
          ),
        ),
      ),
      h(
        'section',
        { class: 'group' },
        h(
          'h2',
          {},
          h(
            'label',
            { class: 'toggle' },
            checkbox(p.soft_collision.enabled, set(p.soft_collision, 'enabled'), {
              name: 'soft-collision',
            }),
            'Soft collision avoidance',
          ),
        ),
        h(
          'p',
          { class: 'hint' },
          'Shoots grow toward open space, away from the leaves of every plant.',
        ),
        h(
          'div',
          { class: 'grid2' },
          field(
            'Cone half angle',
            numberInput(p.soft_collision.cone[0], cone(p.soft_collision.cone, 0), {
              min: 1,
              max: 179,
              name: 'soft-half-angle',
            }),
            { unit: '°', title: 'degrees from the growth direction, 0 to 180' },
          ),
          field(
            'Look-ahead',
            numberInput(p.soft_collision.cone[1], cone(p.soft_collision.cone, 1), {
              min: 0.001,
              max: 100,
              step: 0.01,
              name: 'soft-look-ahead',
            }),
            { unit: 'm', title: 'ray length, m' },
          ),
          field(
            'Rays',
            numberInput(p.soft_collision.cone[2], cone(p.soft_collision.cone, 2), {
              min: 8,
              max: 16384,
              integer: true,
              name: 'soft-rays',
            }),
            { title: 'rays per cone, 8 to 16384' },
          ),
          field(
            'Inertia',
            numberInput(p.soft_collision.cone[3], cone(p.soft_collision.cone, 3), {
              min: 0,
              max: 1,
              step: 0.05,
              name: 'soft-inertia',
            }),
            { title: '0 turns fully to open space, 1 leaves growth unchanged' },
          ),
        ),
      ),
      h(
        'section',
        { class: 'group' },
        h('h2', {}, 'Solid obstacles'),
        field('OBJ files, one per line', files, {
          wide: true,
          title: 'relative to the output folder',
        }),
        h(
          'div',
          { class: 'grid2' },
          field(
            'Avoid distance',
            numberInput(p.obstacles.avoid_distance, set(p.obstacles, 'avoid_distance'), {
              min: 0,
              step: 0.05,
              name: 'avoid-distance',
            }),
            { unit: 'm' },
          ),
          field(
            'Fruit adjustment',
            checkbox(p.obstacles.fruit_adjustment, set(p.obstacles, 'fruit_adjustment'), {
              name: 'fruit-adjustment',
            }),
            { title: 'fruit hanging into an obstacle are turned out of it' },
          ),
        ),
      ),
      h(
        'section',
        { class: 'group' },
        h(
          'h2',
          {},
          h(
            'label',
            { class: 'toggle' },
            checkbox(p.attraction.enabled, set(p.attraction, 'enabled'), { name: 'attraction' }),
            'Attraction points',
          ),
        ),
        field('Points x y z, one per line', points, { unit: 'm', wide: true }),
        pointsError,
        field('Points file (CSV x,y,z)', attractionFile, { wide: true }),
        h(
          'div',
          { class: 'grid2' },
          field(
            'Cone half angle',
            numberInput(p.attraction.cone[0], cone(p.attraction.cone, 0), {
              min: 1,
              max: 179,
              name: 'attraction-half-angle',
            }),
            { unit: '°' },
          ),
          field(
            'Look-ahead',
            numberInput(p.attraction.cone[1], cone(p.attraction.cone, 1), {
              min: 0.001,
              step: 0.05,
              name: 'attraction-look-ahead',
            }),
            { unit: 'm' },
          ),
          field(
            'Inertia',
            numberInput(p.attraction.cone[2], cone(p.attraction.cone, 2), {
              min: 0,
              max: 1,
              step: 0.05,
              name: 'attraction-inertia',
            }),
          ),
        ),
      ),
      physiologySection(this.app),
    );
  }
}
