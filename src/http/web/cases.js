// The cases of the API as forms: every input by its JSON pointer (the API's
// field), the paper's symbol, a unit (SI shown; any consistent units work)
// and the range the API's schema gives it (openapi/openapi.json; the browser
// test checks these ranges against that document).

// A scalar input. `range`: {min, max, exclusiveMin, exclusiveMax}.
function field(path, sym, unit, text, range = {}, extra = {}) {
  return { kind: 'field', path, sym, unit, text, range, ...extra };
}

// A vector input: one field per component, under one legend.
function vector(path, sym, unit, text, components = ['x', 'y'], extra = {}) {
  return {
    kind: 'vector', path, sym, unit, text,
    fields: components.map((c) => field(`${path}/${c}`, `${sym}<sub>${c}</sub>`, unit, `${text}, ${c}`, extra.range || {}, { component: c })),
  };
}

const POSITIVE = { min: 0, exclusiveMin: true };
const NON_NEGATIVE = { min: 0 };
const UNIT_INTERVAL = { min: 0, max: 1 };
const SIGNED_UNIT = { min: -1, max: 1 };

// A group of inputs under a legend.
const group = (legend, parts, extra = {}) => ({ kind: 'group', legend, parts, ...extra });
// One of several sets of inputs, chosen by radio buttons; `detect` picks the
// option a request uses.
const choice = (id, legend, options, detect) => ({ kind: 'choice', id, legend, options, detect });
// Inputs present or absent as a whole (a second body, the twist law).
const toggle = (id, label, parts, present) => ({ kind: 'toggle', id, label, parts, present });

const restitution = () => field('/restitution', 'e', '', 'kinematic coefficient of restitution (Eq 1)', UNIT_INTERVAL);
const friction = (text = 'Coulomb friction coefficient') => field('/friction', 'f', '', text, NON_NEGATIVE);
const tangentialRestitution = () =>
  field('/tangential_restitution', 'e<sub>t</sub>', '', 'tangential coefficient of restitution (Eq 20); −1: no tangential impulse', SIGNED_UNIT);
const kinetic = () => [
  field('/kinetic_restitution/value', 'R', '', 'kinetic coefficient of restitution P<sub>n</sub><sup>R</sup>/P<sub>n</sub><sup>A</sup> (Eq 9)', UNIT_INTERVAL),
  field('/kinetic_restitution/approach_impulse_ratio', 'μ<sub>A</sub>', '', 'impulse ratio of the approach phase (Eq 12)'),
  field('/kinetic_restitution/rebound_impulse_ratio', 'μ<sub>R</sub>', '', 'impulse ratio of the rebound phase (Eq 13)'),
];

// The paper's frame: one body against a barrier.
const paperBody = (inertiaOptional) => group('Body', [
  field('/body/mass', 'm', 'kg', 'mass', POSITIVE),
  field('/body/inertia', 'I', 'kg m²', inertiaOptional ? 'centroidal moment of inertia m k²; blank: a point mass' : 'centroidal moment of inertia m k²', POSITIVE),
]);
const paperContact = (optional) => group('Contact: G from C', [
  field('/contact/tangential_offset', 'd<sub>c</sub>', 'm', 'offset of G from C along t'),
  field('/contact/normal_offset', 'd<sub>d</sub>', 'm', 'offset of G from C along n (a disc on the barrier: its radius)'),
], { note: optional ? 'rigid body only; blank for a point mass' : '' });
const paperVelocity = () => group('Initial velocity', [
  field('/velocity/normal', 'v<sub>n</sub>', 'm/s', 'normal velocity of G; the contact must approach: v<sub>n</sub> + d<sub>c</sub> ω < 0'),
  field('/velocity/tangential', 'v<sub>t</sub>', 'm/s', 'tangential velocity of G'),
  field('/velocity/angular', 'ω', 'rad/s', 'angular velocity, positive turning n toward t'),
]);

// A lamina in world axes (planar case), body `i`.
const lamina = (i) => [
  field(`/bodies/${i}/mass`, 'm', 'kg', 'mass', POSITIVE),
  field(`/bodies/${i}/inertia`, 'I', 'kg m²', 'moment of inertia about G', POSITIVE),
  vector(`/bodies/${i}/position`, 'G', 'm', 'position of the mass centre'),
  vector(`/bodies/${i}/velocity`, 'v', 'm/s', 'velocity of G'),
  field(`/bodies/${i}/angular_velocity`, 'ω', 'rad/s', 'angular velocity, counter-clockwise positive'),
];

const coulombApproach = () => field('/kinetic_restitution/approach_friction', 'f<sub>A</sub>', '', 'Coulomb friction of the approach phase', NON_NEGATIVE);

// Which two-phase law a request holds.
const twoPhase = (r) => ('approach_friction' in r.kinetic_restitution ? 'kinetic-coulomb' : 'kinetic');

const XYZ = ['x', 'y', 'z'];
// The two-phase law with ratios as magnitudes (space, and a Coulomb approach
// in the plane): R, the approach phase's member, μ_R along the approach.
const kineticMagnitudes = (approach) => [
  field('/kinetic_restitution/value', 'R', '', 'kinetic coefficient of restitution P<sub>n</sub><sup>R</sup>/P<sub>n</sub><sup>A</sup> (Eq 9)', UNIT_INTERVAL),
  approach,
  // No lower bound on the page: the member's schema is the plane's too, where
  // a ratio may be negative; the service refuses a negative one in space.
  field('/kinetic_restitution/rebound_impulse_ratio', 'μ<sub>R</sub>', '', 'rebound phase |P<sub>t</sub>|/P<sub>n</sub> (≥ 0), along the approach’s direction'),
];

// A rigid body in space (spatial case), body `i`.
const rigid = (i) => {
  const p = `/bodies/${i}`;
  return [
    field(`${p}/mass`, 'm', 'kg', 'mass', POSITIVE),
    choice(`inertia-${i}`, 'Inertia about G', [
      { id: 'sphere', label: 'sphere', parts: [
        field(`${p}/inertia/sphere/radius`, 'r', 'm', 'radius: I = (2/5) m r² solid, (2/3) m r² hollow', POSITIVE),
        field(`${p}/inertia/sphere/hollow`, '', '', 'hollow (a thin shell: tennis ball)', {}, { type: 'checkbox' }),
      ] },
      { id: 'principal', label: 'principal moments', parts: [
        vector(`${p}/inertia/principal/moments`, 'I', 'kg m²', 'principal moments about the body axes (> 0)', XYZ),
        vector(`${p}/inertia/principal/rotation`, 'q', '', 'rotation of the body axes, a quaternion (blank: identity)', ['w', 'x', 'y', 'z']),
      ] },
      { id: 'tensor', label: 'tensor', parts: [
        vector(`${p}/inertia`, 'I', 'kg m²', 'inertia tensor in world axes (I<sub>xy</sub> = −∫xy dm)', ['xx', 'yy', 'zz', 'xy', 'xz', 'yz']),
      ] },
    ], (r) => {
      const inertia = r?.bodies?.[i]?.inertia || {};
      return 'principal' in inertia ? 'principal' : 'xx' in inertia ? 'tensor' : 'sphere';
    }),
    vector(`${p}/position`, 'G', 'm', 'position of the mass centre', XYZ),
    vector(`${p}/velocity`, 'v', 'm/s', 'velocity of G', XYZ),
    vector(`${p}/angular_velocity`, 'ω', 'rad/s', 'angular velocity', XYZ),
  ];
};

const hasBodyB = (r) => Array.isArray(r?.bodies) && r.bodies.length > 1;
// Body A, body B or a barrier, and the contact in world axes: the opening
// parts of the two-body cases, `body(i)` being the fields of body i.
const bodiesAndContact = (body, components) => [
  group('Body A', body(0)),
  toggle('body-b', 'Body B (unchecked: A hits a fixed barrier)', [group('Body B', body(1))], hasBodyB),
  group('Contact', [
    vector('/contact/point', 'C', 'm', 'contact point', components),
    vector('/contact/normal', 'n', '', 'normal from B into A, any length', components),
  ]),
];

export const CASES = [
  {
    id: 'normal', title: 'Normal', endpoint: '/v1/impacts/normal', section: 'section 2.1',
    about: 'A point mass, or a rigid body without friction, against a barrier.',
    parts: [paperBody(true), paperContact(true), paperVelocity(), group('Coefficient', [restitution()])],
  },
  {
    id: 'oblique', title: 'Oblique', endpoint: '/v1/impacts/oblique', section: 'Eqs 1–19, Appendix',
    about: 'A rigid body against a barrier: e with Coulomb friction f or a prescribed impulse ratio μ, or the two-phase kinetic R.',
    parts: [
      paperBody(false), paperContact(false), paperVelocity(),
      choice('law', 'Tangential law', [
        { id: 'friction', label: 'friction f', parts: [restitution(), friction('Coulomb friction coefficient; the ratio is capped by μ<sub>c</sub>')] },
        { id: 'ratio', label: 'impulse ratio μ', parts: [restitution(), field('/impulse_ratio', 'μ', '', 'prescribed impulse ratio P<sub>t</sub>/P<sub>n</sub> (Eq 2)')] },
        { id: 'kinetic', label: 'kinetic R', parts: kinetic() },
        { id: 'kinetic-coulomb', label: 'kinetic R, Coulomb approach', parts: kineticMagnitudes(coulombApproach()) },
      ], (r) => ('kinetic_restitution' in r ? twoPhase(r) : 'impulse_ratio' in r ? 'ratio' : 'friction')),
    ],
  },
  {
    id: 'tangential', title: 'Tangential', endpoint: '/v1/impacts/tangential', section: 'Eqs 20–27',
    about: 'Bilinear tangential restitution e<sub>t</sub>, capped by friction f.',
    parts: [
      paperBody(false), paperContact(false), paperVelocity(),
      group('Coefficients', [restitution(), friction('Coulomb friction coefficient, the cap of the tangential impulse'), tangentialRestitution()]),
    ],
  },
  {
    id: 'torsional', title: 'Torsional', endpoint: '/v1/impacts/torsional', section: 'Eqs 28–31',
    about: 'A body spinning about the contact normal: torsional restitution e<sub>z</sub> capped by torsional friction μ<sub>z</sub>.',
    parts: [
      group('Body', [
        field('/body/mass', 'm', 'kg', 'mass', POSITIVE),
        field('/body/normal_inertia', 'I<sub>n</sub>', 'kg m²', 'moment of inertia about the normal', POSITIVE),
      ]),
      group('Initial velocity', [
        field('/velocity/normal', 'v<sub>n</sub>', 'm/s', 'normal velocity (approaching)', { max: 0, exclusiveMax: true }),
        field('/velocity/spin', 'ω<sub>n</sub>', 'rad/s', 'spin about the normal'),
      ]),
      group('Coefficients', [
        field('/restitution', 'e', '', 'coefficient of restitution of the normal impact', UNIT_INTERVAL),
        field('/torsion/restitution', 'e<sub>z</sub>', '', 'torsional coefficient of restitution (Eq 28)', UNIT_INTERVAL),
        field('/torsion/friction', 'μ<sub>z</sub>', '', 'torsional friction coefficient', NON_NEGATIVE),
        field('/torsion/pitch_radius', 'ρ<sub>p</sub>', 'm', 'pitch radius of the torsional friction impulse', POSITIVE),
      ]),
    ],
  },
  {
    id: 'planar', title: 'Planar, two bodies', endpoint: '/v1/impacts/planar', section: 'world axes',
    about: 'Two laminae, or one against a fixed barrier, in world axes; the normal n points from B (or the barrier) into A.',
    parts: [
      ...bodiesAndContact(lamina),
      choice('law', 'Law', [
        { id: 'friction', label: 'friction f', parts: [restitution(), friction()] },
        { id: 'ratio', label: 'impulse ratio μ', parts: [restitution(), field('/impulse_ratio', 'μ', '', 'prescribed signed ratio P<sub>t</sub>/P<sub>n</sub> along t = ẑ × n')] },
        { id: 'tangential', label: 'tangential e<sub>t</sub>', parts: [restitution(), friction(), tangentialRestitution()] },
        { id: 'frictionless', label: 'frictionless', parts: [restitution()] },
        { id: 'kinetic', label: 'kinetic R', parts: kinetic() },
        { id: 'kinetic-coulomb', label: 'kinetic R, Coulomb approach', parts: kineticMagnitudes(coulombApproach()) },
      ], (r) => ('kinetic_restitution' in r ? twoPhase(r) : 'tangential_restitution' in r ? 'tangential'
        : 'impulse_ratio' in r ? 'ratio' : 'friction' in r ? 'friction' : 'frictionless')),
    ],
  },
  {
    id: 'spatial', title: 'Spatial, two bodies', endpoint: '/v1/impacts/spatial', section: 'in space',
    about: 'Two rigid bodies, or one against a fixed barrier, in space: slip in any direction, an optional twist law about the normal.',
    parts: [
      ...bodiesAndContact(rigid, XYZ),
      choice('law', 'Tangential law', [
        { id: 'friction', label: 'friction f', parts: [restitution(), friction()] },
        { id: 'ratio', label: 'impulse ratio μ', parts: [restitution(), field('/impulse_ratio', 'μ', '', 'prescribed ratio |P<sub>t</sub>|/P<sub>n</sub>, opposing the slip', NON_NEGATIVE)] },
        { id: 'tangential', label: 'tangential e<sub>t</sub>', parts: [restitution(), friction(), tangentialRestitution()] },
        { id: 'frictionless', label: 'frictionless', parts: [restitution()] },
        { id: 'kinetic', label: 'kinetic R', parts: kineticMagnitudes(field('/kinetic_restitution/approach_impulse_ratio', 'μ<sub>A</sub>', '', 'approach phase |P<sub>t</sub>|/P<sub>n</sub> (≥ 0), opposing the slip')) },
        { id: 'kinetic-coulomb', label: 'kinetic R, Coulomb approach', parts: kineticMagnitudes(coulombApproach()) },
      ], (r) => ('kinetic_restitution' in r ? twoPhase(r)
        : 'tangential_restitution' in r ? 'tangential' : 'impulse_ratio' in r ? 'ratio'
        : 'friction' in r ? 'friction' : 'frictionless')),
      toggle('twist', 'Twist law about the normal', [group('Twist', [
        field('/torsion/restitution', 'e<sub>z</sub>', '', 'torsional coefficient of restitution', UNIT_INTERVAL),
        field('/torsion/friction', 'μ<sub>z</sub>', '', 'torsional friction coefficient', NON_NEGATIVE),
        field('/torsion/pitch_radius', 'ρ<sub>p</sub>', 'm', 'pitch radius of the torsional friction', POSITIVE),
      ])], (r) => r && 'torsion' in r),
    ],
  },
];

// A request per case for a first visit (the API's own schema examples).
export const DEFAULTS = {
  normal: { body: { mass: 2.0 }, velocity: { normal: -3.0 }, restitution: 0.5 },
  oblique: {
    body: { mass: 1.0, inertia: 0.00125 }, contact: { tangential_offset: 0.0, normal_offset: 0.05 },
    velocity: { normal: -1.0, tangential: 0.4, angular: 0.0 }, restitution: 0.93, friction: 0.123,
  },
  tangential: {
    body: { mass: 1.0, inertia: 0.00125 }, contact: { tangential_offset: 0.0, normal_offset: 0.05 },
    velocity: { normal: -1.0, tangential: 0.4, angular: 0.0 }, restitution: 0.93, friction: 0.123, tangential_restitution: 0.34,
  },
  torsional: {
    body: { mass: 0.6, normal_inertia: 0.003456 }, velocity: { normal: -3.0, spin: 20.0 }, restitution: 0.7,
    torsion: { restitution: 0.2, friction: 0.3, pitch_radius: 0.01 },
  },
};

export const caseById = (id) => CASES.find((c) => c.id === id) || CASES[1];

// Every field of a case (whatever option or toggle holds it), in form order.
export function allFields(spec) {
  const out = [];
  const walk = (parts) => {
    for (const p of parts) {
      if (p.kind === 'field') out.push(p);
      else if (p.kind === 'vector') out.push(...p.fields);
      else if (p.kind === 'group' || p.kind === 'toggle') walk(p.parts);
      else if (p.kind === 'choice') p.options.forEach((o) => walk(o.parts));
    }
  };
  walk(spec.parts);
  return out;
}

// The range as text: "> 0", "[0, 1]", "≥ 0", "< 0".
export function rangeText(range) {
  const { min, max, exclusiveMin, exclusiveMax } = range;
  if (min !== undefined && max !== undefined) {
    return `${exclusiveMin ? '(' : '['}${fmtBound(min)}, ${fmtBound(max)}${exclusiveMax ? ')' : ']'}`;
  }
  if (min !== undefined) return `${exclusiveMin ? '>' : '≥'} ${fmtBound(min)}`;
  if (max !== undefined) return `${exclusiveMax ? '<' : '≤'} ${fmtBound(max)}`;
  return '';
}
const fmtBound = (x) => String(x).replace('-', '−');

// The outputs' labels and units, from the service's quantity table
// (/assets/quantities.json, made from the solver's declarations): the page
// holds no list of its own. `setQuantities` is given the table at start-up.
const QUANTITIES = new Map();

export function setQuantities(table) {
  QUANTITIES.clear();
  for (const c of table?.cases || []) {
    for (const q of [...c.inputs, ...c.outputs]) QUANTITIES.set(q.path, q);
  }
}

// The paper's symbol as HTML: `V_ct` → V<sub>ct</sub>.
const symbolHtml = (symbol) => {
  const [base, ...sub] = symbol.split('_');
  const escape = (t) => t.replace(/&/g, '&amp;').replace(/</g, '&lt;');
  return sub.length ? `${escape(base)}<sub>${escape(sub.join('_'))}</sub>` : escape(base);
};

// A response member's label: {sym (HTML), text, unit}; a member the table
// does not name (the precision) by its pointer.
export function outputLabel(pointer) {
  const q = QUANTITIES.get(pointer);
  if (!q) return { sym: '', text: pointer.replace(/^\//, ''), unit: '' };
  const named = q.unit === '';
  return {
    sym: named ? '' : symbolHtml(q.symbol),
    text: q.name,
    unit: named || q.unit === '1' ? '' : q.unit,
  };
}
