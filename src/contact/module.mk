# Layer: contact. Modules and the objects of the modules each one uses.
MODULES += contact contact_geometry contact_master_multipliers contact_mortar contact_results contact_status tie_constraints contact_heat contact_wear edge_tree
$(OBJDIR)/contact.o: $(OBJDIR)/cfe_element.o $(OBJDIR)/contact_geometry.o $(OBJDIR)/edge_tree.o $(OBJDIR)/contact_master_multipliers.o $(OBJDIR)/contact_mortar.o $(OBJDIR)/contact_wear.o $(OBJDIR)/element_catalogue.o $(OBJDIR)/element_interface.o $(OBJDIR)/growable.o $(OBJDIR)/kinds.o $(OBJDIR)/mesh_topology.o $(OBJDIR)/messages.o $(OBJDIR)/model.o $(OBJDIR)/shape_functions.o $(OBJDIR)/strings.o
$(OBJDIR)/contact_mortar.o: $(OBJDIR)/contact_geometry.o $(OBJDIR)/edge_tree.o $(OBJDIR)/growable.o $(OBJDIR)/kinds.o $(OBJDIR)/model.o $(OBJDIR)/shape_functions.o \
                            $(OBJDIR)/small_matrices.o
$(OBJDIR)/contact_master_multipliers.o: $(OBJDIR)/contact_geometry.o $(OBJDIR)/contact_mortar.o $(OBJDIR)/edge_tree.o $(OBJDIR)/kinds.o \
                                        $(OBJDIR)/model.o $(OBJDIR)/shape_functions.o
$(OBJDIR)/contact_geometry.o: $(OBJDIR)/element_catalogue.o $(OBJDIR)/kinds.o $(OBJDIR)/model.o $(OBJDIR)/shape_functions.o
$(OBJDIR)/contact_results.o: $(OBJDIR)/contact.o $(OBJDIR)/contact_geometry.o $(OBJDIR)/kinds.o $(OBJDIR)/model.o
$(OBJDIR)/tie_constraints.o: $(OBJDIR)/contact_geometry.o $(OBJDIR)/contact_mortar.o $(OBJDIR)/edge_tree.o $(OBJDIR)/kinds.o $(OBJDIR)/messages.o $(OBJDIR)/model.o $(OBJDIR)/strings.o
$(OBJDIR)/contact_status.o: $(OBJDIR)/contact.o $(OBJDIR)/kinds.o $(OBJDIR)/model.o
$(OBJDIR)/contact_heat.o: $(OBJDIR)/contact.o $(OBJDIR)/element_catalogue.o $(OBJDIR)/kinds.o $(OBJDIR)/model.o $(OBJDIR)/shape_functions.o
$(OBJDIR)/contact_wear.o: $(OBJDIR)/contact_geometry.o $(OBJDIR)/kinds.o $(OBJDIR)/model.o
$(OBJDIR)/edge_tree.o: $(OBJDIR)/contact_geometry.o $(OBJDIR)/growable.o $(OBJDIR)/kinds.o $(OBJDIR)/model.o
